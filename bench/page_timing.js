// kinema page's targets (issue 35), measured in headless chromium: the file's size, the time
// from opening it to its first frame drawn, and frame times while it plays with arrows,
// paths, polygons and instant centres on (requestAnimationFrame deltas kept by the page); where
// the page has dimension sliders, the time a slider move takes to solve every row again (40
// moves of the first slider, the first 10 left out while the script warms up) and to redraw.
// Written in docs/page.md.
//   node bench/page_timing.js PAGE.html CHROMIUM MODULES_DIR   (MODULES_DIR: build/tests/browser/node_modules)
'use strict';
const fs = require('fs');
const path = require('path');
const [html, chromiumPath, modulesDir] = process.argv.slice(2);
const { chromium } = require(path.resolve(modulesDir, 'playwright-core'));
(async () => {
  const args = process.getuid && process.getuid() === 0 ? ['--no-sandbox'] : [];
  const browser = await chromium.launch({ executablePath: chromiumPath, args: args });
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  const started = Date.now();
  await page.goto('file://' + path.resolve(html));
  // The first frame: the next animation frame after the page's script has drawn row 0.
  await page.evaluate(() => new Promise((done) => requestAnimationFrame(() => done())));
  const firstFrame = Date.now() - started;
  const navigation = await page.evaluate(() => performance.getEntriesByType('navigation')[0].toJSON());
  await page.evaluate(() => {
    document.getElementById('show-acceleration').click();
    const centres = document.getElementById('show-centres');
    if (centres) centres.click();
    document.getElementById('speed').value = '60';
    window.kinemaPage.setPlaying(true);
  });
  await page.waitForTimeout(3000);
  const times = await page.evaluate(() => window.kinemaPage.frameTimes.slice().sort((a, b) => a - b));
  const draws = await page.evaluate(() => window.kinemaPage.drawTimes.slice().sort((a, b) => a - b));
  const sliders = await page.evaluate(() => {
    const input = document.querySelector('#sliders input');
    if (!input) return null;
    window.kinemaPage.setPlaying(false);
    const name = input.getAttribute('data-parameter'), file = Number(input.value), step = Number(input.step);
    const moves = [];
    for (let k = 0; k < 40; ++k) {
      const begun = performance.now();
      window.kinemaPage.setDimensions({ [name]: file + (k % 2 ? 1 : -1) * 10 * step });
      moves.push(performance.now() - begun);
    }
    return { solve: window.kinemaPage.resolveTimes.slice(-30), move: moves.slice(10) };
  });
  const quantile = (list, q) => Math.round(100 * list[Math.min(list.length - 1, Math.floor(q * list.length))]) / 100;
  const at = (q) => quantile(times, q);
  console.log(JSON.stringify({
    bytes: fs.statSync(html).size,
    opened_to_first_frame_ms: firstFrame,
    dom_content_loaded_ms: Math.round(navigation.domContentLoadedEventEnd),
    frames: times.length,
    frame_ms_median: at(0.5), frame_ms_p95: at(0.95),
    frames_per_second: Math.round(1000 / at(0.5)),
    draw_ms_median: quantile(draws, 0.5), draw_ms_p95: quantile(draws, 0.95),
    slider_solve_ms_median: sliders ? quantile(sliders.solve.sort((a, b) => a - b), 0.5) : null,
    slider_solve_ms_max: sliders ? quantile(sliders.solve, 1) : null,
    slider_move_ms_median: sliders ? quantile(sliders.move.sort((a, b) => a - b), 0.5) : null,
  }));
  await browser.close();
})();
