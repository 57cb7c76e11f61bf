// kinema page in a real browser (Debian's chromium, driven by npm's playwright-core): for
// every sample, the page kinema writes loads with no console error and no request but the
// file itself; at three values set through the scrubber each joint is drawn where
// `kinema eval --format csv` puts it (within 0.1 px); the readout holds eval's CSV row (each
// cell's data-value and title, the copied text) and shows it as the text table does (eval's
// CSV at 6 digits), round-off as 0: at every value of the run no value shown is below 1e-12 of
// its field's largest magnitude over the run unless it is 0;
// the drawing at two values differs and is not blank; each point's image in the velocity and
// acceleration polygons is its velocity and acceleration in eval's row, and every pair of bodies
// has its instant centre drawn (or listed as not found); a spatial chain's points are drawn in
// 3-D where eval puts them, projected, and dragging turns it; the derivation is laid out as
// MathML. A singular row and an unassembled
// range show as such; a hostile title, description and file name run no script, a hostile
// joint or link name is refused. A dimension
// slider moved in the four-bar's, a slider-crank's and Problem 4.4's pages solves the rows
// again as `kinema eval` solves the file edited to that dimension (1e-12), and a rocker too
// short to close shows its rows as not assembled.
//
//   node page_test.js KINEMA SAMPLES_DIR WORK_DIR CHROMIUM MODULES_DIR
'use strict';
const { execFileSync } = require('child_process');
const fs = require('fs');
const path = require('path');
const assert = require('assert');

const [kinema, samplesDir, workDir, chromiumPath, modulesDir] = process.argv.slice(2);
const { chromium } = require(path.join(modulesDir, 'playwright-core'));
fs.mkdirSync(workDir, { recursive: true });

// The same values for the page and for eval: a turn in 4 deg steps, two seconds of a
// timed chain, the piston's stroke and beyond (its last values do not assemble).
function sweepFor(header) {
  const input = header.split(',')[0];
  if (input.endsWith('[deg]')) return '0:356:4';
  if (input.endsWith('[s]')) return '0:2:0.05';
  return '120:220:2';
}

function run(args) { return execFileSync(kinema, args, { encoding: 'utf8' }); }

function pageAndCsv(file, name) {
  const sweep = sweepFor(run(['eval', file, '--format', 'csv']).split('\n')[0]);
  const html = path.join(workDir, name + '.html');
  run(['page', file, '--sweep', sweep, '-o', html]);
  const csv = run(['eval', file, '--sweep', sweep, '--format', 'csv', '-q']).trimEnd().split('\n');
  // The text table's digits: the same formatter at its 6 significant.
  const six = run(['eval', file, '--sweep', sweep, '--format', 'csv', '--precision', '6', '-q']).trimEnd().split('\n');
  return { html: html, header: csv[0].split(','), rows: csv.slice(1), tableRows: six.slice(1) };
}

// The readout at every value of the run: each field holds the full value of eval's CSV row
// and shows what the text table shows (eval's CSV at 6 significant digits), or 0 where that
// is round-off: no value shown is below 1e-12 of its field's largest magnitude over the run
// unless it is 0, and a value shown as 0 is below 1e-12 of the larger of that and the
// problem's size for its kind (which kinema writes with the field). At three rows set
// through the scrubber the cells show it, each with its full value (data-value, title), and
// the copy box and a copy of the selected cells give the full values. Returns how many
// values were round-off shown as 0.
async function checkReadout(page, name, header, rows, tableRows, picks) {
  const seen = await page.evaluate((n) => {
    const sizes = JSON.parse(document.getElementById('kinema-data').textContent).columns.fields.map((f) => f.size);
    const readouts = [];
    for (let r = 0; r < n; ++r) readouts.push(window.kinemaPage.readout(r));
    return { readouts: readouts, sizes: sizes };
  }, rows.length);
  const full = rows.map((r) => r.split(',')), table = tableRows.map((r) => r.split(','));
  const number = (text) => (text !== '' && isFinite(Number(text)) ? Number(text) : NaN);
  const largest = full[0].map((unused, k) => Math.max(0, ...full.map((f) => (isNaN(number(f[k])) ? 0 : Math.abs(number(f[k]))))));
  let zeroed = 0;
  seen.readouts.forEach((fields, r) => {
    assert.deepStrictEqual(fields.map((f) => f.full), full[r], `${name}: the readout's full values at row ${r} are not eval's CSV row`);
    fields.forEach((field, k) => {
      const text = field.shown, value = number(full[r][k]);
      if (isNaN(value)) {  // the status, the note, an undefined value: as they are
        assert.strictEqual(text, full[r][k], `${name}: row ${r} ${header[k]}`);
        return;
      }
      assert(text === '0' || Math.abs(Number(text)) >= 1e-12 * largest[k],
        `${name}: row ${r} ${header[k]} shows ${text}, round-off beside ${largest[k]} in its field over the run`);
      if (text === table[r][k]) return;
      assert.strictEqual(text, '0', `${name}: row ${r} ${header[k]} shows ${text}, the text table ${table[r][k]}`);
      assert(Math.abs(value) < 1e-12 * Math.max(largest[k], seen.sizes[k] || 0),
        `${name}: row ${r} ${header[k]} = ${value} is shown as 0 beside ${largest[k]} (size ${seen.sizes[k]})`);
      ++zeroed;
    });
  });
  const valuesOf = (box) => box.split('\n').slice(0, -1).map((line) => line.split('\t')[1]);  // a line a field, each ended
  for (const row of picks) {
    await scrubTo(page, row);
    const cells = await page.evaluate(() => {
      const tds = Array.from(document.querySelectorAll('#readout td'));
      // Cells selected and copied: the full values, a line a field.
      const selection = window.getSelection();
      selection.selectAllChildren(document.getElementById('readout'));
      const copied = new DataTransfer();
      document.getElementById('readout').dispatchEvent(new ClipboardEvent('copy', { clipboardData: copied, bubbles: true, cancelable: true }));
      selection.removeAllRanges();
      return { shown: tds.map((c) => c.textContent), full: tds.map((c) => c.getAttribute('data-value')), titles: tds.map((c) => c.title),
               box: document.getElementById('readout-text').value, copied: copied.getData('text/plain') };
    });
    assert.deepStrictEqual(cells.shown, seen.readouts[row].map((f) => f.shown), `${name}: the readout's cells at row ${row}`);
    assert.deepStrictEqual(cells.full, full[row], `${name}: the readout's data-value at row ${row}`);
    assert.deepStrictEqual(cells.titles, full[row], `${name}: the readout's titles at row ${row}`);
    assert.deepStrictEqual(valuesOf(cells.box), full[row], `${name}: the copy box at row ${row} holds other than eval's CSV row`);
    assert.deepStrictEqual(valuesOf(cells.copied), full[row], `${name}: the selected readout at row ${row} copied as other than eval's CSV row`);
  }
  return zeroed;
}

// One tab for every page (a new tab costs more than the page): each file opened in it with
// what it logs, requests and asks collected from then on.
let tab = null;
const seen = { errors: [], requests: [], dialogs: [] };
async function open(browser, html) {
  if (!tab) {
    tab = await browser.newPage({ viewport: { width: 1100, height: 800 } });
    tab.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') seen.errors.push(m.text()); });
    tab.on('pageerror', (e) => seen.errors.push(e.message));
    tab.on('request', (r) => seen.requests.push(r.url()));
    tab.on('dialog', (d) => { seen.dialogs.push(d.message()); d.dismiss(); });
  }
  for (const list of Object.values(seen)) list.length = 0;
  await tab.goto('file://' + html);
  return { page: tab, seen: seen };
}

async function scrubTo(page, row) {
  await page.evaluate((r) => {
    const s = document.getElementById('scrubber');
    s.value = r;
    s.dispatchEvent(new Event('input'));
  }, row);
}

// What the page shows at the current row: the readout, the view, the joints drawn.
function shown(page) {
  return page.evaluate(() => {
    const svg = document.getElementById('mechanism');
    return {
      readout: Array.from(document.querySelectorAll('#readout td')).map((td) => td.getAttribute('data-value')).join(','),
      scale: Number(svg.getAttribute('data-scale')),
      ox: Number(svg.getAttribute('data-ox')),
      oy: Number(svg.getAttribute('data-oy')),
      status: svg.getAttribute('data-status'),
      statusText: document.getElementById('status').textContent,
      joints: Array.from(svg.querySelectorAll('[data-joint]')).map((j) => {
        const m = /translate\(([^,]+),([^)]+)\)/.exec(j.getAttribute('transform'));
        return { name: j.getAttribute('data-name'), x: Number(j.getAttribute('data-x')), y: Number(j.getAttribute('data-y')),
                 px: Number(m[1]), py: Number(m[2]) };
      }),
    };
  });
}

// Each named joint at the CSV's position of its point, read back in pixels.
function checkJoints(name, header, csvRow, view) {
  const fields = csvRow.split(',');
  let checked = 0;
  for (const joint of view.joints) {
    const column = header.findIndex((h) => h.startsWith(joint.name + '_x ['));
    if (!joint.name || column < 0) continue;
    const x = Number(fields[column]), y = Number(fields[column + 1]);
    const px = view.ox + x * view.scale, py = view.oy - y * view.scale;
    assert(Math.abs(joint.px - px) <= 0.1 && Math.abs(joint.py - py) <= 0.1,
      `${name}: joint ${joint.name} drawn at (${joint.px}, ${joint.py}) px, eval puts it at (${px}, ${py})`);
    assert(Math.abs(joint.x - x) * view.scale <= 0.1 && Math.abs(joint.y - y) * view.scale <= 0.1,
      `${name}: joint ${joint.name}'s data-x/y (${joint.x}, ${joint.y}) is not eval's (${x}, ${y})`);
    ++checked;
  }
  return checked;
}

// The polygons of the row: the image of each named point in the velocity polygon is its
// velocity in eval's row, in the acceleration polygon its acceleration (to the 5 digits the
// page draws them with). Returns how many images were checked.
// A number as the page writes it for people: "25000", "0.5", "2\u00d710\u2076", "10\u207b\u2074".
function numberOf(text) {
  const m = /^(-?[0-9.]*?)\u00d7?10([\u207b\u2070\u00b9\u00b2\u00b3\u2074-\u2079]+)$/.exec(text);
  if (!m) return Number(text);
  const digits = '\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079';
  const power = Number(Array.from(m[2]).map((c) => (c === '\u207b' ? '-' : String(digits.indexOf(c)))).join(''));
  return (m[1] === '' ? 1 : m[1] === '-' ? -1 : Number(m[1])) * Math.pow(10, power);
}

async function checkPolygons(page, name, header, csvRow) {
  const fields = csvRow.split(',').map(Number);
  const polygons = await page.evaluate(() => ['velocity-polygon', 'acceleration-polygon'].map((id) => {
    const panel = document.getElementById(id);
    return panel ? Array.from(panel.querySelectorAll('[data-vertex]')).map((v) => ({
      name: v.getAttribute('data-vertex'), x: Number(v.getAttribute('data-x')), y: Number(v.getAttribute('data-y')) })) : null;
  }));
  if (!polygons[0]) return 0;
  // Each panel's scale bar: its length, not written out in six digits or more ("1000000 mm/s^2").
  const bars = await page.evaluate(() => ['velocity-polygon', 'acceleration-polygon'].map((id) => {
    const panel = document.getElementById(id);
    return { text: panel.querySelector('text.tick').textContent, perPixel: Number(panel.getAttribute('data-per-pixel')) };
  }));
  // Each vertex's name clear of every arrow's head (a small polygon's names were drawn
  // over the heads), the panel one unit a pixel, the polygon filling a third of it or more.
  const layouts = await page.evaluate(() => ['velocity-polygon', 'acceleration-polygon'].map((id) => {
    const panel = document.getElementById(id);
    const box = panel.getBoundingClientRect(), view = panel.viewBox.baseVal;
    const heads = Array.from(panel.querySelectorAll('line[data-arrow]')).map((l) => {
      const [x1, y1, x2, y2] = ['x1', 'y1', 'x2', 'y2'].map((a) => Number(l.getAttribute(a)));
      const length = Math.hypot(x2 - x1, y2 - y1), u = [(x2 - x1) / length, (y2 - y1) / length];
      const back = Math.min(9, length);  // the marker: 6 x 1.6 px long, half as wide each side
      const corners = [[x2, y2], [x2 - u[0] * back - u[1] * 4, y2 - u[1] * back + u[0] * 4], [x2 - u[0] * back + u[1] * 4, y2 - u[1] * back - u[0] * 4]];
      return { name: l.getAttribute('data-arrow'), x0: Math.min(...corners.map((c) => c[0])), x1: Math.max(...corners.map((c) => c[0])),
        y0: Math.min(...corners.map((c) => c[1])), y1: Math.max(...corners.map((c) => c[1])) };
    });
    const labels = Array.from(panel.querySelectorAll('text.label')).map((t) => {
      const b = t.getBBox();
      return { text: t.textContent, x0: b.x, x1: b.x + b.width, y0: b.y, y1: b.y + b.height };
    });
    const marks = Array.from(panel.querySelectorAll('[data-vertex]')).map((m) => m.getBoundingClientRect());
    const span = marks.length ? [Math.max(...marks.map((m) => m.right)) - Math.min(...marks.map((m) => m.left)),
      Math.max(...marks.map((m) => m.bottom)) - Math.min(...marks.map((m) => m.top))] : [0, 0];
    return { drawn: [box.width, box.height], view: [view.width, view.height], heads: heads, labels: labels, span: span };
  }));
  for (const layout of layouts) {
    assert(Math.abs(layout.view[0] - layout.drawn[0]) <= 1 && Math.abs(layout.view[1] - layout.drawn[1]) <= 1,
      `${name}: a polygon panel of ${layout.view} units drawn ${layout.drawn} px`);
    const atOnePoint = layout.span[0] < 8 && layout.span[1] < 8;  // every image at the pole: nothing to fit
    assert(atOnePoint || layout.span[0] >= (layout.drawn[0] - 60) / 1.6 || layout.span[1] >= 200 / 1.6,
      `${name}: a polygon of ${layout.span} px in a panel of ${layout.drawn} px`);
    for (const l of layout.labels)
      for (const h of layout.heads)
        assert(!(l.x0 < h.x1 - 0.5 && h.x0 + 0.5 < l.x1 && l.y0 < h.y1 - 0.5 && h.y0 + 0.5 < l.y1),
          `${name}: the polygon's label "${l.text}" (${l.x0.toFixed(1)}, ${l.y0.toFixed(1)})-(${l.x1.toFixed(1)}, ${l.y1.toFixed(1)}) covers the head of ${h.name}`);
  }
  // Issue 49: the arrows named, a legend for their kinds, normal and tangential parts told
  // apart by their dashes, and no head on an arrow too short for one (piled heads).
  const marks = await page.evaluate(() => ['velocity-polygon', 'acceleration-polygon'].map((id) => {
    const panel = document.getElementById(id);
    const arrows = Array.from(panel.querySelectorAll('line[data-arrow]')).map((l) => {
      const [x1, y1, x2, y2] = ['x1', 'y1', 'x2', 'y2'].map((a) => Number(l.getAttribute(a)));
      return { name: l.getAttribute('data-arrow'), kind: l.getAttribute('class').split(' ').find((c) => c.startsWith('polygon-') && c !== 'polygon-arrow'),
               length: Math.hypot(x2 - x1, y2 - y1), head: l.hasAttribute('marker-end'), dash: getComputedStyle(l).strokeDasharray };
    });
    const legend = Array.from(panel.parentNode.querySelectorAll('[data-legend]')).map((e) => 'polygon-' + e.getAttribute('data-legend'));
    const labelled = Array.from(panel.querySelectorAll('[data-arrow-label]')).map((e) => e.getAttribute('data-arrow-label'));
    return { arrows, legend, labelled };
  }));
  for (const m of marks) {
    const long = m.arrows.filter((a) => a.length >= 20);
    const named = long.filter((a) => m.labelled.includes(a.name)).length;
    assert(named >= 0.75 * long.length, `${name}: ${named} of ${long.length} polygon arrows named`);
    for (const a of m.arrows) {
      assert(m.legend.includes(a.kind), `${name}: the polygon's legend has no ${a.kind}`);
      assert(a.head === (a.length >= 14), `${name}: the arrow ${a.name} of ${a.length.toFixed(1)} px ${a.head ? 'has' : 'has no'} head`);
    }
    const dashes = (kind) => new Set(m.arrows.filter((a) => a.kind === kind).map((a) => a.dash));
    for (const normal of dashes('polygon-normal'))
      assert(!dashes('polygon-tangential').has(normal), `${name}: normal and tangential parts drawn with one dash ${normal}`);
  }
  for (const bar of bars) {
    const [number] = bar.text.split(' ');
    assert(!/[0-9]{6}/.test(number) && Math.abs(numberOf(number) - 50 * bar.perPixel) <= 1e-9 * 50 * bar.perPixel,
      `${name}: the polygon's scale bar "${bar.text}" for 50 px at ${bar.perPixel} a pixel`);
  }
  let checked = 0;
  [['_vx [', polygons[0]], ['_ax [', polygons[1]]].forEach(([suffix, vertices]) => {
    const size = Math.max(...vertices.map((v) => Math.hypot(v.x, v.y)));
    assert(vertices.some((v) => v.name === 'o' && v.x === 0 && v.y === 0), `${name}: a polygon without its pole o at 0`);
    for (const v of vertices) {
      const column = header.findIndex((h) => h.startsWith(v.name + suffix));
      if (column < 0) continue;
      const x = fields[column], y = fields[column + 1];
      assert(Math.abs(v.x - x) <= 1e-4 * size && Math.abs(v.y - y) <= 1e-4 * size,
        `${name}: ${v.name} of the ${suffix === '_vx [' ? 'velocity' : 'acceleration'} polygon at (${v.x}, ${v.y}), eval's (${x}, ${y})`);
      ++checked;
    }
  });
  return checked;
}

// The velocity and acceleration arrows at the current value: every arrow from a point in the
// panel ends in it (near the piston's toggle the accelerations ran thousands of pixels off
// the panel); one stopped at the edge has its magnitude written there, which is the
// point's speed or acceleration in eval's row. Returns how many were stopped.
async function checkArrows(page, name, header, csvRow) {
  const fields = csvRow.split(',').map(Number);
  const found = await page.evaluate(() => {
    const box = document.getElementById('show-acceleration');
    if (!box.checked) box.click();
    const svg = document.getElementById('mechanism'), size = svg.getBoundingClientRect();
    const arrows = Array.from(svg.querySelectorAll('#overlay line.velocity, #overlay line.acceleration')).map((l) => ({
      kind: l.classList.contains('velocity') ? 'velocity' : 'acceleration', beyond: l.hasAttribute('data-beyond'),
      from: [Number(l.getAttribute('x1')), Number(l.getAttribute('y1'))], to: [Number(l.getAttribute('x2')), Number(l.getAttribute('y2'))] }));
    const written = Array.from(svg.querySelectorAll('#overlay text.arrow-beyond')).map((t) => t.textContent);
    const boxes = Array.from(svg.querySelectorAll('#overlay text.arrow-beyond')).map((t) => t.getBBox());
    const overlapping = boxes.some((b, i) => boxes.some((o, j) => j > i && b.x < o.x + o.width && o.x < b.x + b.width && b.y < o.y + o.height && o.y < b.y + b.height));
    box.click();
    return { width: size.width, height: size.height, arrows: arrows, written: written, overlapping: overlapping };
  });
  assert(!found.overlapping, `${name}: the magnitudes of arrows beyond the panel written over each other: ${found.written}`);
  const inside = (c) => c[0] >= 0 && c[0] <= found.width && c[1] >= 0 && c[1] <= found.height;
  const beyond = found.arrows.filter((a) => a.beyond);
  for (const a of found.arrows)
    if (inside(a.from)) assert(inside(a.to), `${name}: a ${a.kind} arrow from (${a.from}) ends beyond the panel at (${a.to})`);
  assert.strictEqual(found.written.length, beyond.length, `${name}: ${beyond.length} arrows stopped at the edge, ${found.written.length} magnitudes written`);
  const magnitudes = header.map((h, k) => (/_(speed|acceleration) \[/.test(h) ? fields[k] : null)).filter((v) => v !== null);
  for (const text of found.written) {
    const value = numberOf(text.split(' ')[0]);
    assert(magnitudes.some((m) => Math.abs(m - value) <= 5e-3 * Math.abs(m)), `${name}: "${text}" is no point's speed or acceleration in eval's row`);
  }
  return beyond.length;
}

// The instant centres with the toggle on: every pair of bodies has its centre drawn (a mark,
// or an arrow toward one at infinity) or is listed as not found; a centre at a joint is there.
async function checkCentres(page, name) {
  const found = await page.evaluate(() => {
    const box = document.getElementById('show-centres');
    if (!box) return null;
    box.click();
    const svg = document.getElementById('mechanism');
    const joints = {};
    svg.querySelectorAll('[data-joint]').forEach((j) => { joints[j.getAttribute('data-name')] = [Number(j.getAttribute('data-x')), Number(j.getAttribute('data-y'))]; });
    const drawn = Array.from(svg.querySelectorAll('#centres [data-centre]')).map((c) => ({
      name: c.getAttribute('data-centre'), x: Number(c.getAttribute('data-x')), y: Number(c.getAttribute('data-y')) }));
    const data = JSON.parse(document.getElementById('kinema-data').textContent);
    const row = Number(document.getElementById('scrubber').value);
    const structure = data.constructions.centre_structures[data.constructions.rows[row].centres[0]];
    // A drawing row as the page unpacks it (its values by their row pattern).
    const unpacked = (packed) => packed && data.drawing.row_patterns[packed[0]].map((k) => packed[1 + k]);
    // The labels of the centres drawn (near-coincident ones were printed over each other).
    const labels = Array.from(svg.querySelectorAll('#centres text.label:not(.centre-label)')).map((t) => {
      const b = t.getBBox();
      return { text: t.textContent, x0: b.x, x1: b.x + b.width, y0: b.y, y1: b.y + b.height };
    });
    // The joints' and points' letters and the links' numbers, which no centre's name covers.
    const frame = svg.getBoundingClientRect();
    const letters = Array.from(svg.querySelectorAll('[data-joint] text, [data-point] text, .link-number')).map((t) => {
      const r = t.getBoundingClientRect();
      return { text: t.textContent, x0: r.left - frame.left, x1: r.right - frame.left, y0: r.top - frame.top, y1: r.bottom - frame.top };
    });
    const names = Array.from(svg.querySelectorAll('#centres text.label:not(.centre-label)')).map((t) => {
      const r = t.getBoundingClientRect();
      return { text: t.textContent, x0: r.left - frame.left, x1: r.right - frame.left, y0: r.top - frame.top, y1: r.bottom - frame.top };
    });
    // Centres beyond the panel, and the arrows at its edge towards them.
    const panel = svg.getBoundingClientRect();
    const beyond = Array.from(svg.querySelectorAll('#centres [data-centre]')).filter((c) => {
      const m = /translate\(([^,]+),([^)]+)\)/.exec(c.getAttribute('transform') || '');
      return m && (Number(m[1]) < 0 || Number(m[1]) > panel.width || Number(m[2]) < 0 || Number(m[2]) > panel.height);
    }).map((c) => c.getAttribute('data-centre'));
    const pointed = Array.from(svg.querySelectorAll('#centres [data-centre-beyond]')).map((a) => {
      const x = [a.getAttribute('x1'), a.getAttribute('x2')].map(Number), y = [a.getAttribute('y1'), a.getAttribute('y2')].map(Number);
      return { name: a.getAttribute('data-centre-beyond'), inside: x.every((v) => v >= 0 && v <= panel.width) && y.every((v) => v >= 0 && v <= panel.height) };
    });
    box.click();
    return { drawn: drawn, joints: joints, structure: structure, jointNames: data.drawing.joint_names, form: data.drawing.form,
      places: unpacked(data.drawing.rows[row]), labels: labels, beyond: beyond, pointed: pointed, letters: letters, names: names };
  });
  if (!found) return false;
  found.labels.forEach((a, i) => found.labels.slice(i + 1).forEach((b) => {
    const across = Math.min(a.x1, b.x1) - Math.max(a.x0, b.x0), down = Math.min(a.y1, b.y1) - Math.max(a.y0, b.y0);
    assert(across <= 0.5 || down <= 0.5, `${name}: centre labels "${a.text}" and "${b.text}" overlap`);
  }));
  for (const a of found.names)
    for (const b of found.letters) {
      const across = Math.min(a.x1, b.x1) - Math.max(a.x0, b.x0), down = Math.min(a.y1, b.y1) - Math.max(a.y0, b.y0);
      assert(across <= 0.5 || down <= 0.5, `${name}: centre label "${a.text}" covers "${b.text}"`);
    }
  for (const c of found.beyond) {
    const arrow = found.pointed.find((a) => c.split(', ').includes(a.name) || a.name === c);
    assert(arrow && arrow.inside, `${name}: centre ${c} is beyond the panel with no arrow at its edge`);
  }
  const n = found.structure.bodies.length;
  const names = new Set(found.drawn.map((c) => c.name));
  assert.strictEqual(names.size + found.structure.not_found.length, (n * (n - 1)) / 2,
    `${name}: ${names.size} centres drawn and ${found.structure.not_found.length} not found of ${(n * (n - 1)) / 2}`);
  // A centre at a joint is drawn there (a vector-loop file's: at the place of its row it names,
  // a vector's end or a block).
  for (const c of found.structure.centres) {
    if (c.joint === null) continue;
    const linkage = found.form === 'linkage';
    const at = linkage ? found.joints[found.jointNames[c.joint]] : [found.places[2 * c.joint], found.places[2 * c.joint + 1]];
    const mark = found.drawn.find((d) => d.name === c.name);
    assert(mark && at && mark.x === at[0] && mark.y === at[1],
      `${name}: ${c.name} is not drawn at ${linkage ? "joint " + found.jointNames[c.joint] : "its place " + c.joint + " of the row"} (${at}): ${JSON.stringify(mark)}`);
  }
  return true;
}

// The plots' scales as a reader sees them: every label inside its chart (a wide one such as
// "-1.50e+3" was cut by the chart's left edge) and left of the plotted area; a value's label
// is 0 or of the size of its range (a speed's minimum of 1e-33 was written so); the input's
// first and last values under the axis, the last with its unit; a chart drawn one unit a
// pixel (a full-width chart's text was stretched to twice its width).
async function checkPlots(page, name, header, rows) {
  const charts = await page.evaluate(() => Array.from(document.querySelectorAll('.plot svg')).map((chart) => {
    const axis = chart.querySelector('line.axis');
    const box = chart.getBoundingClientRect(), view = chart.viewBox.baseVal;
    return {
      drawn: [box.width, box.height], view: [view.width, view.height],
      left: Math.min(Number(axis.getAttribute('x1')), Number(axis.getAttribute('x2'))),
      labels: Array.from(chart.querySelectorAll('text.tick')).map((t) => {
        const b = t.getBBox();
        return { text: t.textContent, x: b.x, y: b.y, right: b.x + b.width, bottom: b.y + b.height };
      }),
    };
  }));
  assert(charts.length >= 1, `${name}: no plot`);
  const input = header[0];
  const unit = /\[(.*)\]$/.exec(input)[1];
  const first = Number(rows[0].split(',')[0]), last = Number(rows[rows.length - 1].split(',')[0]);
  for (const chart of charts) {
    assert(Math.abs(chart.view[0] - chart.drawn[0]) <= 1 && Math.abs(chart.view[1] - chart.drawn[1]) <= 1,
      `${name}: a plot of ${chart.view} units drawn ${chart.drawn} px (its text stretched)`);
    for (const l of chart.labels)
      assert(l.x >= 0 && l.right <= chart.view[0] && l.y >= 0 && l.bottom <= 200, `${name}: the plot label "${l.text}" is cut: (${l.x}, ${l.y})-(${l.right}, ${l.bottom}) outside ${chart.view[0]} x 200`);
    // Round ticks (issue 49; the raw minimum and maximum were the only two): at least two
    // up the side and along the input, a round step apart (1, 2, 2.5 or 5 times a power of
    // ten; a turn's 45, 90 or 180 deg), no two labels touching.
    const scale = chart.labels.filter((l) => l.bottom < 190);
    assert(scale.length >= 2, `${name}: a plot with ${scale.length} scale values`);
    for (const l of scale) assert(l.right <= chart.left, `${name}: the scale value "${l.text}" overlaps the plot (${l.right} > ${chart.left})`);
    for (const l of scale) assert(!/[0-9]{6}/.test(l.text), `${name}: the scale value "${l.text}" written out`);
    const values = scale.map((l) => numberOf(l.text));
    assertRoundSteps(values, `${name}: the scale values ${values}`);
    for (let i = 1; i < scale.length; ++i)
      assert(scale[i].y >= scale[i - 1].bottom || scale[i - 1].y >= scale[i].bottom, `${name}: the scale values ${scale[i - 1].text} and ${scale[i].text} overlap`);
    const axis = chart.labels.filter((l) => l.bottom >= 190);
    assert(axis.length >= 2, `${name}: a plot's input axis with ${axis.length} values`);
    assert(axis[axis.length - 1].text.endsWith(' ' + unit), `${name}: the input axis's last value "${axis[axis.length - 1].text}" without its unit ${unit}`);
    const inputs = axis.map((l) => numberOf(l.text.replace(' ' + unit, '')));
    assertRoundSteps(inputs, `${name}: the input axis ${inputs}`, unit === 'deg');
    const span = Math.abs(last - first);
    assert(inputs[0] >= Math.min(first, last) - 1e-9 * span && inputs[inputs.length - 1] <= Math.max(first, last) + 1e-9 * span,
      `${name}: the input axis ${inputs} outside the run ${first} to ${last}`);
    for (let i = 1; i < axis.length; ++i)
      assert(axis[i].x >= axis[i - 1].right, `${name}: the input axis's ${axis[i - 1].text} and ${axis[i].text} overlap`);
  }
}

// Values a round step apart: equal steps of 1, 2, 2.5 or 5 times a power of ten (of 45, 90
// or 180 where a turn of degrees may be ticked so), to the labels' three digits.
function assertRoundSteps(values, what, degrees) {
  const sorted = values.slice().sort((a, b) => a - b);
  const step = sorted[1] - sorted[0];
  assert(step > 0, `${what}: two ticks at one value`);
  for (let i = 2; i < sorted.length; ++i)
    assert(Math.abs(sorted[i] - sorted[i - 1] - step) <= 0.02 * step, `${what}: ticks not evenly spaced`);
  const mantissa = step / Math.pow(10, Math.floor(Math.log10(step) + 1e-9));
  const round = [1, 2, 2.5, 5, 10].some((m) => Math.abs(mantissa - m) <= 0.01 * m) || (degrees && [45, 90, 180].includes(Math.round(step)));
  assert(round, `${what}: a step of ${step}, not a round one`);
  for (const v of sorted) assert(Math.abs(v / step - Math.round(v / step)) <= 0.02, `${what}: ${v} is not a multiple of the step ${step}`);
}

// A spatial chain in 3-D: each point drawn at eval's position (data-x/y/z) and at its
// projection in pixels (turned by yaw about z and pitch, about the motion's centre: the
// page's data-yaw, data-pitch, data-centre), every frame drawn; dragging turns the view.
async function checkChain(page, name, header, rows, picks) {
  for (const row of picks) {
    await scrubTo(page, row);
    const view = await page.evaluate(() => {
      const svg = document.getElementById('mechanism');
      const attribute = (n) => Number(svg.getAttribute(n));
      return {
        scale: attribute('data-scale'), ox: attribute('data-ox'), oy: attribute('data-oy'), yaw: attribute('data-yaw'),
        pitch: attribute('data-pitch'), centre: svg.getAttribute('data-centre').split(',').map(Number),
        frames: svg.querySelectorAll('[data-frame]').length,
        points: Array.from(svg.querySelectorAll('#overlay [data-point]')).map((p) => {
          const m = /translate\(([^,]+),([^)]+)\)/.exec(p.getAttribute('transform'));
          return { name: p.getAttribute('data-point'), x: Number(p.getAttribute('data-x')), y: Number(p.getAttribute('data-y')),
                   z: Number(p.getAttribute('data-z')), px: Number(m[1]), py: Number(m[2]) };
        }),
      };
    });
    if (name === 'rssr_spatial_four_bar') await checkRssrBodies(page, row);
    const fields = rows[row].split(',');
    assert(view.frames >= 2, `${name}: ${view.frames} frames drawn`);
    assert(view.points.length >= 1, `${name}: no point drawn`);
    for (const p of view.points) {
      const column = header.findIndex((h) => h.startsWith(p.name + '_x ['));
      const at = [0, 1, 2].map((k) => Number(fields[column + k]));
      assert.deepStrictEqual([p.x, p.y, p.z], at, `${name}: point ${p.name}'s place is not eval's`);
      const d = at.map((v, k) => v - view.centre[k]);
      const u = Math.cos(view.yaw) * d[0] - Math.sin(view.yaw) * d[1];
      const v = Math.cos(view.pitch) * d[2] + Math.sin(view.pitch) * (Math.sin(view.yaw) * d[0] + Math.cos(view.yaw) * d[1]);
      const px = view.ox + u * view.scale, py = view.oy - v * view.scale;
      assert(Math.abs(p.px - px) <= 0.1 && Math.abs(p.py - py) <= 0.1, `${name}: point ${p.name} drawn at (${p.px}, ${p.py}), projected (${px}, ${py})`);
    }
  }
  // Fitted to the motion as seen (every row's points inside the panel, filling it in one
  // direction): fitted to the sphere that holds the motion, the arm took a third of it.
  const fit = await page.evaluate(() => {
    const svg = document.getElementById('mechanism');
    const attribute = (n) => Number(svg.getAttribute(n));
    const box = svg.getBoundingClientRect();
    return { scale: attribute('data-scale'), ox: attribute('data-ox'), oy: attribute('data-oy'), yaw: attribute('data-yaw'),
             pitch: attribute('data-pitch'), centre: svg.getAttribute('data-centre').split(',').map(Number),
             width: box.width, height: box.height,
             names: Array.from(svg.querySelectorAll('#overlay [data-point]')).map((p) => p.getAttribute('data-point')) };
  });
  const seen = [];
  header.forEach((h, column) => {
    if (!fit.names.some((point) => h.startsWith(point + '_x ['))) return;
    rows.forEach((line) => {
      const fields = line.split(',');
      const d = [0, 1, 2].map((k) => Number(fields[column + k]) - fit.centre[k]);
      if (!d.every(Number.isFinite)) return;
      const u = Math.cos(fit.yaw) * d[0] - Math.sin(fit.yaw) * d[1];
      const v = Math.cos(fit.pitch) * d[2] + Math.sin(fit.pitch) * (Math.sin(fit.yaw) * d[0] + Math.cos(fit.yaw) * d[1]);
      seen.push([fit.ox + u * fit.scale, fit.oy - v * fit.scale]);
    });
  });
  const xs = seen.map((p) => p[0]), ys = seen.map((p) => p[1]);
  const spread = Math.max((Math.max(...xs) - Math.min(...xs)) / fit.width, (Math.max(...ys) - Math.min(...ys)) / fit.height);
  assert(seen.length > 0 && Math.min(...xs) >= 0 && Math.max(...xs) <= fit.width && Math.min(...ys) >= 0 && Math.max(...ys) <= fit.height,
    `${name}: a point drawn outside the panel at the fit: x ${Math.min(...xs)}..${Math.max(...xs)} of ${fit.width}, y ${Math.min(...ys)}..${Math.max(...ys)} of ${fit.height}`);
  assert(spread >= 0.45, `${name}: the motion's points fill ${spread.toFixed(2)} of the panel at the fit`);
  const before = await drawingShot(page);
  const opened = fit.yaw;
  const box = await page.locator('#mechanism').boundingBox();
  await page.mouse.move(box.x + 200, box.y + 200);
  await page.mouse.down();
  await page.mouse.move(box.x + 260, box.y + 220, { steps: 3 });
  await page.mouse.up();
  const yaw = await page.evaluate(() => Number(document.getElementById('mechanism').getAttribute('data-yaw')));
  const after = await drawingShot(page);
  assert(Math.abs(yaw - opened) > 0.1, `${name}: dragging did not turn the chain`);
  assert(!before.equals(after), `${name}: the chain looks the same after turning`);
}

// Issue 49: the RSSR was drawn as its frames joined to the observer's origin, B and C
// floating. Now: the crank A-B, the rocker D-C and the coupler B-C as bars between the
// places drawn, A and D on ground pivots and lettered, no bar from A to D.
async function checkRssrBodies(page, row) {
  const drawn = await page.evaluate(() => {
    const svg = document.getElementById('mechanism');
    const at = (e) => { const m = /translate\(([^,]+),([^)]+)\)/.exec(e.getAttribute('transform')); return [Number(m[1]), Number(m[2])]; };
    const places = {};
    svg.querySelectorAll('[data-frame]').forEach((f) => { places[f.getAttribute('data-frame')] = at(f); });
    svg.querySelectorAll('#overlay [data-point]').forEach((p) => { places[p.getAttribute('data-point')] = at(p); });
    return {
      places,
      bars: Array.from(svg.querySelectorAll('line.bar-line')).map((l) => ['x1', 'y1', 'x2', 'y2'].map((a) => Number(l.getAttribute(a)))),
      pivots: Array.from(svg.querySelectorAll('path.pivot')).map((p) => p.getAttribute('d').slice(1).split(' ')[0].split(',').map(Number)),
      couplers: Array.from(svg.querySelectorAll('[data-coupler]')).map((g) => g.getAttribute('data-coupler')),
      letters: Array.from(svg.querySelectorAll('[data-joint-letter]')).map((j) => j.getAttribute('data-joint-letter')).sort(),
    };
  });
  const near = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1]) <= 0.1;
  const joined = (a, b) => drawn.bars.filter((l) => (near(l.slice(0, 2), a) && near(l.slice(2), b)) || (near(l.slice(0, 2), b) && near(l.slice(2), a))).length;
  const { crank, rocker, B, C } = drawn.places;
  assert(crank && rocker && B && C, `rssr row ${row}: places drawn ${Object.keys(drawn.places)}`);
  assert.strictEqual(drawn.bars.length, 3, `rssr row ${row}: ${drawn.bars.length} bars drawn, not the crank, coupler and rocker`);
  assert.strictEqual(joined(crank, B), 1, `rssr row ${row}: no crank A-B`);
  assert.strictEqual(joined(rocker, C), 1, `rssr row ${row}: no rocker D-C`);
  assert.strictEqual(joined(B, C), 1, `rssr row ${row}: no coupler B-C`);
  assert.strictEqual(joined(crank, rocker), 0, `rssr row ${row}: a bar from A to D`);
  assert.deepStrictEqual(drawn.couplers, ['BC'], `rssr row ${row}: couplers ${drawn.couplers}`);
  assert(drawn.pivots.length === 2 && [crank, rocker].every((f) => drawn.pivots.some((p) => near(p, f))),
    `rssr row ${row}: ground pivots at ${JSON.stringify(drawn.pivots)}, frames at ${crank} and ${rocker}`);
  assert.deepStrictEqual(drawn.letters, ['A', 'D'], `rssr row ${row}: joints lettered ${drawn.letters}`);
}

// The drawing's pixels (a clip of the tab: quicker than an element's screenshot, which waits
// for the element to be still and scrolled into view).
async function drawingShot(page) {
  const box = await page.evaluate(() => {
    const r = document.getElementById('mechanism').getBoundingClientRect();
    return { x: r.left, y: r.top, width: r.width, height: r.height };
  });
  return page.screenshot({ clip: box, animations: 'disabled', caret: 'initial' });
}

// Issue 49: the page's labels collided as the mechanism moved (problem_4_4_joints at 150
// deg: a velocity arrow over link number 4, I24 into I03; problem_3_22_joints: an arrowhead
// over "O2"). At 12 values over the run, with both arrows and the instant centres on: no
// name, link number or centre's name on another, nor on an arrow's head.
async function checkLabelsClear(page, name, rows) {
  const ok = rows.map((r, k) => (r.split(',')[3] === 'ok' ? k : -1)).filter((k) => k >= 0);
  const turnedOn = await page.evaluate(() => ['show-velocity', 'show-acceleration', 'show-centres'].filter((id) => {
    const box = document.getElementById(id);
    if (!box || box.checked) return false;
    box.click();
    return true;
  }));
  for (let k = 0; k < 12; ++k) {
    const row = ok[Math.floor((k * (ok.length - 1)) / 11)];
    await scrubTo(page, row);
    const found = await page.evaluate(() => {
      const svg = document.getElementById('mechanism'), panel = svg.getBoundingClientRect();
      const box = (e) => { const r = e.getBoundingClientRect(); return { x0: r.left - panel.left, y0: r.top - panel.top, x1: r.right - panel.left, y1: r.bottom - panel.top }; };
      const labels = Array.from(svg.querySelectorAll('[data-joint] > text, [data-point] > text, .link-number circle, #centres text'))
        .filter((e) => e.textContent !== '' || e.tagName === 'circle').map((e) => ({ text: e.textContent || 'link number', ...box(e) }))
        .filter((b) => b.x1 > b.x0 && b.x1 > 0 && b.y1 > 0 && b.x0 < panel.width && b.y0 < panel.height);  // seen
      const heads = Array.from(svg.querySelectorAll('#overlay line[marker-end]')).filter((l) => /velocity|acceleration/.test(l.getAttribute('class'))).map((l) => {
        const [x1, y1, x2, y2] = ['x1', 'y1', 'x2', 'y2'].map((a) => Number(l.getAttribute(a)));
        const length = Math.hypot(x2 - x1, y2 - y1) || 1, u = [(x2 - x1) / length, (y2 - y1) / length];
        const back = Math.min(8, length);
        const corners = [[x2, y2], [x2 - u[0] * back - u[1] * 3, y2 - u[1] * back + u[0] * 3], [x2 - u[0] * back + u[1] * 3, y2 - u[1] * back - u[0] * 3]];
        return { x0: Math.min(...corners.map((c) => c[0])), x1: Math.max(...corners.map((c) => c[0])),
                 y0: Math.min(...corners.map((c) => c[1])), y1: Math.max(...corners.map((c) => c[1])) };
      });
      return { labels, heads };
    });
    const overlap = (a, b) => a.x0 < b.x1 - 1 && b.x0 < a.x1 - 1 && a.y0 < b.y1 - 1 && b.y0 < a.y1 - 1;
    for (let i = 0; i < found.labels.length; ++i) {
      for (let j = 0; j < i; ++j)
        assert(!overlap(found.labels[i], found.labels[j]), `${name} row ${row}: "${found.labels[i].text}" on "${found.labels[j].text}"`);
      for (const h of found.heads) assert(!overlap(found.labels[i], h), `${name} row ${row}: "${found.labels[i].text}" on an arrow's head`);
    }
  }
  await page.evaluate((ids) => { for (const id of ids) document.getElementById(id).click(); }, turnedOn);
}

async function checkSample(browser, file) {
  const name = path.basename(file, '.toml');
  const { html, header, rows, tableRows } = pageAndCsv(file, name);
  const { page, seen } = await open(browser, html);
  const spatial = header.some((h) => /_z \[/.test(h));
  const count = await page.evaluate(() => Number(document.getElementById('scrubber').max) + 1);
  assert.strictEqual(count, rows.length, `${name}: the scrubber has ${count} values, eval ${rows.length} rows`);
  // Three values where the mechanism is assembled and regular, spread over the run.
  const ok = rows.map((r, k) => (r.split(',')[3] === 'ok' ? k : -1)).filter((k) => k >= 0);
  const picks = [ok[Math.floor(ok.length / 6)], ok[Math.floor(ok.length / 2)], ok[Math.floor((5 * ok.length) / 6)]];
  await checkPlots(page, name, header, rows);
  // Issue 49: the four-bar's coupler carries P: one plate through A, B and P, as the worked
  // solution draws it (two bars before), at every value picked.
  if (name === 'four_bar') {
    for (const row of picks) {
      await scrubTo(page, row);
      const plates = await page.evaluate(() => Array.from(document.querySelectorAll('#mechanism polygon.plate'))
        .map((p) => p.getAttribute('points').trim().split(/\s+/).length));
      assert(plates.includes(3), `four_bar row ${row}: the coupler with P is not drawn as a plate (${JSON.stringify(plates)})`);
    }
  }
  if (!spatial) {  // at the value the page opens at (the piston's: next to its toggle)
    const opened = await page.evaluate(() => Number(document.getElementById('scrubber').value));
    arrowsBeyond[name] = await checkArrows(page, name, header, rows[opened]);
  }
  let joints = 0;
  for (const row of picks) {
    await scrubTo(page, row);
    const view = await shown(page);
    assert.strictEqual(view.readout, rows[row], `${name}: the readout's values at row ${row} are not eval's CSV row`);
    if (spatial) continue;
    joints += checkJoints(name, header, rows[row], view);
    // Issue 49: a vector-loop file's pivots lettered as its lengths name them (AB, CD: the
    // origin A, the pivot D at (La, Lb)), as the worked solution letters them.
    if (name === 'problem_4_4_six_bar') {
      const at = (letter) => view.joints.find((j) => j.name === letter);
      assert(at('A') && Math.hypot(at('A').x, at('A').y) <= 1e-12, `${name} row ${row}: pivot A not lettered at the origin`);
      assert(at('D') && Math.hypot(at('D').x - 0.3, at('D').y - 0.45) <= 1e-12, `${name} row ${row}: pivot D not lettered at (La, Lb)`);
    }
    constructions.images += await checkPolygons(page, name, header, rows[row]);
    await checkArrows(page, name, header, rows[row]);
    if (await checkCentres(page, name)) constructions.centres.add(name);
  }
  if (!spatial) {
    assert(joints >= 3, `${name}: no joint of the drawing is named by a point of eval's rows`);
    await checkLabelsClear(page, name, rows);
    await scrubTo(page, picks[0]);
    const first = await drawingShot(page);
    await scrubTo(page, picks[2]);
    const second = await drawingShot(page);
    await page.evaluate(() => { for (const id of ['drawing', 'overlay', 'traces']) document.getElementById(id).style.display = 'none'; });
    const blank = await drawingShot(page);
    assert(!first.equals(second), `${name}: the drawing is the same at two values`);
    assert(!first.equals(blank) && !second.equals(blank), `${name}: a drawing is blank`);
  } else {
    await checkChain(page, name, header, rows, picks);
  }
  readoutZeros[name] = await checkReadout(page, name, header, rows, tableRows, picks);
  // The derivation, opened: MathML laid out as formulas (a block as high as its rows), the
  // symbols as kinema derive writes them.
  const derivation = await page.evaluate(() => {
    const details = document.getElementById('derivation');
    details.open = true;
    const blocks = Array.from(details.querySelectorAll('math[display="block"]'));
    const rows = details.querySelectorAll('math[display="block"] > mtable > mtr').length;
    const box = blocks.length ? blocks[0].getBoundingClientRect() : { width: 0, height: 0 };
    const text = details.textContent;
    details.open = false;
    return { blocks: blocks.length, rows: rows, width: box.width, height: box.height, text: text };
  });
  assert(derivation.blocks >= 1 && derivation.rows >= 3, `${name}: the derivation has ${derivation.blocks} formulas, ${derivation.rows} rows`);
  assert(derivation.width > 100 && derivation.height > 10 * Math.min(derivation.rows, 3), `${name}: the derivation is not laid out (${derivation.width} x ${derivation.height})`);
  assert(/[θωφα]/.test(derivation.text), `${name}: the derivation shows no Greek symbol`);
  assert.deepStrictEqual(seen.errors, [], `${name}: console errors`);
  assert.deepStrictEqual(seen.requests, ['file://' + html], `${name}: requests other than the file`);
}

// Rows that are singular or unassembled: marked on the scrubber at exactly those rows, said in
// words when scrubbed to, and not drawn as if assembled.
async function checkFailedRows(browser, file, status) {
  const name = path.basename(file, '.toml');
  const { html, rows } = pageAndCsv(file, name + '_' + status);
  const { page, seen } = await open(browser, html);
  const expected = rows.map((r, k) => (r.split(',')[3] === status ? k : -1)).filter((k) => k >= 0);
  assert(expected.length > 0, `${name}: no ${status} row to show`);
  const marked = await page.evaluate((s) => Array.from(document.querySelectorAll('.mark-' + s)).map((m) => Number(m.getAttribute('data-row'))), status);
  assert.deepStrictEqual(marked, expected, `${name}: the scrubber's ${status} marks`);
  // Opened at the first row that assembles.
  const opened = await page.evaluate(() => Number(document.getElementById('scrubber').value));
  assert.strictEqual(opened, rows.findIndex((r) => r.split(',')[3] === 'ok'), `${name}: opened at row ${opened}`);
  await scrubTo(page, expected[0]);
  const view = await shown(page);
  assert.strictEqual(view.status, status);
  assert.strictEqual(view.readout, rows[expected[0]], `${name}: the readout of a ${status} row`);
  assert(view.statusText.startsWith(status === 'singular' ? 'Singular: ' : 'Not assembled: ') && view.statusText.length > 20,
    `${name}: the ${status} row's reason in words: "${view.statusText}"`);
  if (status === 'unassembled') {
    assert.strictEqual(view.joints.length, 0, `${name}: an unassembled row is drawn`);
  } else {
    const faded = await page.evaluate(() => document.querySelectorAll('#drawing .singular-drawing').length);
    assert(faded > 0, `${name}: a singular row is drawn as if regular`);
  }
  assert.deepStrictEqual(seen.errors, [], `${name}: console errors`);
}

// Dimension sliders: a slider moved to a new value solves every row again in the page; each
// row equals `kinema eval` of the file edited to that value (17 digits) to 1e-12 relative on
// every coordinate, rate, second rate and point value (relative to the larger of the value
// and a column's largest, for values that are rounding noise about 0), with the same status;
// the joints drawn there are eval's points. Returns the slider's value and the page's rows.
async function checkSlider(browser, sampleName, parameter, target, sweep) {
  const file = path.join(samplesDir, sampleName + '.toml');
  const html = path.join(workDir, sampleName + '_sliders.html');
  run(['page', file, '--sweep', sweep, '-o', html]);
  const { page, seen } = await open(browser, html);
  const set = await page.evaluate(([name, value]) => {
    const input = document.querySelector('#sliders input[data-parameter="' + name + '"]');
    input.value = value;
    input.dispatchEvent(new Event('input'));
    return { value: input.value, shown: input.closest('.slider').querySelector('.shown').textContent };
  }, [parameter, target]);
  assert(set.value !== undefined && Number(set.value) === target, `${sampleName}: slider ${parameter} at ${set.value}, not ${target}`);
  const unit = set.shown.split(' ').pop();
  // The file edited to the slider's value, in the unit the slider shows.
  const edited = path.join(workDir, sampleName + '_' + parameter + '.toml');
  const text = fs.readFileSync(file, 'utf8');
  const line = new RegExp('^' + parameter + ' = .*$', 'm');
  assert(line.test(text), `${sampleName}: no line for ${parameter}`);
  fs.writeFileSync(edited, text.replace(line, `${parameter} = "${set.value} ${unit}"`));
  const csv = run(['eval', edited, '--sweep', sweep, '--format', 'csv', '--precision', '17', '-q']).trimEnd().split('\n');
  const header = csv[0].split(','), expected = csv.slice(1).map((r) => r.split(','));
  const got = await page.evaluate(() => window.kinemaPage.rows());
  assert.strictEqual(got.length, expected.length, `${sampleName}: ${got.length} rows in the page, eval ${expected.length}`);
  const largest = header.map((h, k) => Math.max(0, ...expected.map((r) => (isFinite(Number(r[k])) && r[k] !== '' ? Math.abs(Number(r[k])) : 0))));
  let compared = 0;
  expected.forEach((fields, r) => {
    assert.strictEqual(got[r].status, fields[3], `${sampleName} ${parameter}=${set.value}: row ${r}'s status`);
    for (let k = 4; k < header.length - 1; ++k) {
      const want = fields[k] === '' ? NaN : Number(fields[k]), have = got[r].fields[k];
      if (isNaN(want)) {
        assert(isNaN(have), `${sampleName}: row ${r} ${header[k]} is ${have} in the page, none in eval`);
        continue;
      }
      const scale = Math.max(Math.abs(want), Math.abs(have), largest[k] * 1e-3);
      assert(Math.abs(have - want) <= 1e-12 * scale,
        `${sampleName} ${parameter}=${set.value}: row ${r} ${header[k]} is ${have} in the page, ${want} in eval`);
      ++compared;
    }
  });
  // A pin is the centre of the two bodies it joins whatever their rates (issue 45): the
  // four-bar at theta2 = 0, its coupler and rocker turning alike (the tape's N / (i D) is
  // 0 / 0 there), has I34 where eval puts B.
  if (sampleName === 'four_bar' && expected[0][3] === 'ok') {
    const found = await page.evaluate(() => window.kinemaPage.centres(0));
    const i34 = found && found.centres.find((c) => c.name === 'I34');
    const bx = header.findIndex((h) => h.startsWith('B_x ['));
    const b = [Number(expected[0][bx]), Number(expected[0][bx + 1])];
    assert(i34 && i34.at && Math.hypot(i34.at[0] - b[0], i34.at[1] - b[1]) <= 1e-9 * Math.max(largest[bx], largest[bx + 1]),
      `four_bar ${parameter}=${set.value}: I34 at theta2 = 0 is ${JSON.stringify(i34)}, B at (${b})`);
  }
  // The joints drawn at a regular row: at eval's points.
  const ok = expected.map((f, r) => (f[3] === 'ok' ? r : -1)).filter((r) => r >= 0);
  if (ok.length) {
    const row = ok[Math.floor(ok.length / 2)];
    await scrubTo(page, row);
    const view = await shown(page);
    const fields = expected[row];
    let joints = 0;
    for (const joint of view.joints) {
      const column = header.findIndex((h) => h.startsWith(joint.name + '_x ['));
      if (!joint.name || column < 0) continue;
      const x = Number(fields[column]), y = Number(fields[column + 1]), size = Math.max(largest[column], largest[column + 1]);
      assert(Math.abs(joint.x - x) <= 1e-12 * size && Math.abs(joint.y - y) <= 1e-12 * size,
        `${sampleName}: joint ${joint.name} drawn at (${joint.x}, ${joint.y}), eval's point at (${x}, ${y})`);
      ++joints;
    }
    // A chain's points (its frames drawn by the re-solved rows): at eval's, and a frame's
    // origin drawn where a point at that origin is (the robot arm's A at E3's).
    const chain = !sampleName.startsWith('robot_arm') ? null : await page.evaluate(() => {
      const mark = (e) => { const m = /translate\(([^,]+),([^)]+)\)/.exec(e.getAttribute('transform') || ''); return m ? [Number(m[1]), Number(m[2])] : [NaN, NaN]; };
      const points = Array.from(document.querySelectorAll('#mechanism [data-point]')).map((e) => ({ name: e.getAttribute('data-point'),
        at: ['data-x', 'data-y', 'data-z'].map((a) => Number(e.getAttribute(a))), px: mark(e) })).filter((p) => isFinite(p.px[0]));
      const frames = {};
      document.querySelectorAll('#mechanism [data-frame]').forEach((e) => { frames[e.getAttribute('data-frame')] = mark(e); });
      return { points: points, frames: frames };
    });
    if (chain) {
      assert(Object.keys(chain.frames).length === 3 && chain.points.length === 3, `${sampleName}: frames ${Object.keys(chain.frames)} and points ${chain.points.map((p) => p.name)} drawn`);
      for (const point of chain.points) {
        const column = header.findIndex((h) => h.startsWith(point.name + '_x ['));
        assert(column >= 0, `${sampleName}: no column for point ${point.name}`);
        point.at.forEach((v, c) => {
          const want = Number(fields[column + c]), size = Math.max(largest[column], largest[column + 1], largest[column + 2]);
          assert(Math.abs(v - want) <= 1e-12 * size, `${sampleName}: point ${point.name} drawn with ${'xyz'[c]} = ${v}, eval ${want}`);
        });
        ++joints;
      }
      const a = chain.points.find((p) => p.name === 'A');
      assert(a && chain.frames.E3 && Math.hypot(a.px[0] - chain.frames.E3[0], a.px[1] - chain.frames.E3[1]) <= 0.1,
        `${sampleName}: frame E3 drawn at ${chain.frames.E3} px, its origin point A at ${a && a.px}`);
    }
    assert(joints >= 1, `${sampleName}: no joint drawn at a point of eval's`);
    // The constructions of re-solved rows: the polygons at this row, the centres at a third
    // of the regular rows (the four-bar's middle row is folded, its centres at joints
    // whatever the dimensions).
    if (!chain) await checkSolvedConstructions(browser, page, sampleName, edited, sweep, ok[Math.floor(ok.length / 3)], header, fields);
  }
  assert.deepStrictEqual(seen.errors, [], `${sampleName}: console errors`);
  return { page: page, compared: compared, statuses: got.map((g) => g.status) };
}

// A re-solved row's constructions (page scrubbed to the row whose CSV fields are `fields`):
// each polygon's images are eval's velocities and accelerations of the edited file; the
// instant centres at row `centresRow` (a vector-loop file's, and a joints-and-links file's:
// both read from the tape's drawing stage) are those the analysis finds for
// the edited file (its own page, written by kinema, at the same row): within 0.1 px where
// drawn, directions at infinity within 2e-5 (the edited page's data writes them to five
// significant digits), the same centres at infinity.
async function checkSolvedConstructions(browser, page, sampleName, edited, sweep, centresRow, header, fields) {
  const got = await page.evaluate((r) => {
    const panels = ['velocity-polygon', 'acceleration-polygon'].map((id) => {
      const panel = document.getElementById(id);
      return Array.from(panel.querySelectorAll('[data-vertex]')).map((v) => ({ name: v.getAttribute('data-vertex'),
        x: Number(v.getAttribute('data-x')), y: Number(v.getAttribute('data-y')) }));
    });
    const svg = document.getElementById('mechanism');
    return { panels: panels, centres: window.kinemaPage.centres(r), scale: Number(svg.getAttribute('data-scale')) };
  }, centresRow);
  let images = 0;
  got.panels.forEach((vertices, k) => {
    const suffix = k === 0 ? '_vx [' : '_ax [';
    for (const v of vertices) {
      const column = header.findIndex((h) => h.startsWith(v.name + suffix));
      if (column < 0) continue;
      const x = Number(fields[column]), y = Number(fields[column + 1]), size = Math.hypot(x, y) + 1e-300;
      assert(Math.abs(v.x - x) <= 1e-12 * size && Math.abs(v.y - y) <= 1e-12 * size,
        `${sampleName}: re-solved ${v.name} of the ${suffix} polygon at (${v.x}, ${v.y}), eval's (${x}, ${y})`);
      ++images;
    }
  });
  assert(images >= 2, `${sampleName}: ${images} images of a re-solved row's polygons checked`);
  constructions.solvedImages += images;
  assert(got.centres, `${sampleName}: no instant centres on a re-solved row`);
  assert(isFinite(got.scale) && got.scale > 0, `${sampleName}: the drawing's scale ${got.scale}`);
  const html = path.join(workDir, sampleName + '_edited.html');
  run(['page', edited, '--sweep', sweep, '-o', html]);
  const other = await browser.newPage({ viewport: { width: 1100, height: 800 } });  // the slider's page stays open
  await other.goto('file://' + html);
  const want = await other.evaluate((r) => window.kinemaPage.centres(r), centresRow);
  await other.close();
  assert(want && want.centres.length === got.centres.centres.length, `${sampleName}: the edited file's centres differ in number`);
  want.centres.forEach((c, k) => {
    const have = got.centres.centres[k];
    assert.strictEqual(have.name, c.name);
    assert.strictEqual(have.infinite, c.infinite, `${sampleName}: ${c.name} at infinity in one page only`);
    if (c.at) {
      assert(have.at && Math.hypot(have.at[0] - c.at[0], have.at[1] - c.at[1]) * got.scale <= 0.1,
        `${sampleName}: re-solved ${c.name} at (${have.at}), the edited file's at (${c.at})`);
    } else if (c.direction) {
      assert(have.direction && Math.hypot(have.direction[0] - c.direction[0], have.direction[1] - c.direction[1]) <= 2e-5,
        `${sampleName}: re-solved ${c.name} toward (${have.direction}), the edited file's (${c.direction})`);
    }
  });
  constructions.solvedCentres += want.centres.length;
}

async function checkSliders(browser) {
  let compared = 0;
  // Joints and links too (solved by Newton in the page, by dyads in eval; drawn and their
  // extra columns from the tape's drawing stage): the six-bar with CE moved (EF follows), the
  // R-RTR-RRT (a block on a turning link, a slider on the ground), and a slider on a moving
  // guide; within 1 % of the file's, as eval takes a joints file only where its lengths agree
  // with its sketch to 1 %. (Not the parallelogram: moved off it, it is a four-bar near its
  // change point, where two Newton solutions agree only to the tolerance over its conditioning.)
  for (const [sample, parameter, value] of [['four_bar', 'b', 150], ['slider_crank', 'b', 120], ['problem_4_4_six_bar', 'CE', 0.276],
    ['problem_4_4_joints', 'CE', 0.232], ['example_4_2_joints', 'DE', 0.201], ['example_4_1_joints', 'BC', 0.302]]) {
    compared += (await checkSlider(browser, sample, parameter, value, '0:356:4')).compared;
  }
  // A spatial chain: its frames placed by the tape's drawing stage, over time.
  compared += (await checkSlider(browser, 'robot_arm_seed000', 'L2', 0.75, '0:6:0.1')).compared;
  // A rocker half as long: the four-bar no longer closes at every crank angle.
  const short = await checkSlider(browser, 'four_bar', 'c', 40, '0:356:4');
  assert(short.statuses.includes('unassembled'), 'four_bar with c = 40 mm: every row assembles');
  const failed = short.statuses.indexOf('unassembled');
  const marked = await short.page.evaluate(() => document.querySelectorAll('.mark-unassembled').length);
  assert.strictEqual(marked, short.statuses.filter((s) => s === 'unassembled').length, 'four_bar c = 40 mm: marks on the scrubber');
  await scrubTo(short.page, failed);
  const view = await shown(short.page);
  assert(view.status === 'unassembled' && view.statusText.startsWith('Not assembled: ') && view.joints.length === 0,
    `four_bar c = 40 mm: row ${failed} shown as "${view.statusText}" with ${view.joints.length} joints`);
  await checkSliderRanges(short.page);
  // A full turn at 1 deg re-solved in the page: the time a slider move takes.
  const timing = await checkSlider(browser, 'four_bar', 'b', 130, '0:359:1');
  const times = await timing.page.evaluate(() => {
    for (let k = 0; k < 20; ++k) window.kinemaPage.setDimensions({ b: 125 + (k % 2) * 5 });
    return window.kinemaPage.resolveTimes.slice(-20).sort((x, y) => x - y);
  });
  console.log(`sliders: ${compared} values equal eval's, ${constructions.solvedImages} polygon images and ${constructions.solvedCentres} instant centres of re-solved rows; a four-bar turn at 1 deg re-solved in ${times[10].toFixed(2)} ms (median of 20, max ${times[19].toFixed(2)} ms)`);
}

// The four-bar's sliders (its page at 4 deg steps open): each slider's ends and band are
// the analysis's range as the page's data writes it (engine/analysis/slider_ranges, SI, in
// the slider's unit here); the rocker just below the band where every value assembles
// leaves rows unassembled, marked on the scrubber, and just above it leaves none.
async function checkSliderRanges(page) {
  const sliders = await page.evaluate(() => {
    const R = JSON.parse(document.getElementById('kinema-data').textContent).resolve;
    return R.parameters.filter((p) => p.slider).map((p) => {
      const input = document.querySelector('#sliders input[data-parameter="' + p.name + '"]');
      const whole = input.closest('.slider').querySelector('.band .whole');
      const factor = p.dimension === 'angle' ? Math.PI / 180 : R.length_per_unit;
      return { name: p.name, range: p.range, factor: factor, min: Number(input.min), max: Number(input.max),
        wholeMin: whole ? Number(whole.getAttribute('data-min')) : null, wholeMax: whole ? Number(whole.getAttribute('data-max')) : null };
    });
  });
  assert.strictEqual(sliders.length, 6, 'four_bar: a slider for each of a, b, c, d, p, delta');
  const near = (shown, si, factor) => Math.abs(shown * factor - si) <= 1e-11 * Math.abs(si);
  for (const s of sliders) {
    for (const [shown, si, what] of [[s.min, s.range.min, 'min'], [s.max, s.range.max, 'max'],
      [s.wholeMin, s.range.whole_min, 'band min'], [s.wholeMax, s.range.whole_max, 'band max']])
      assert(near(shown, si, s.factor), `four_bar slider ${s.name}: ${what} ${shown}, the data's ${si / s.factor}`);
  }
  const rocker = sliders.find((s) => s.name === 'c');
  const failedAt = async (value) => {
    await page.evaluate((v) => window.kinemaPage.setDimensions({ c: v }), value);
    return page.evaluate(() => ({
      unassembled: window.kinemaPage.rows().filter((r) => r.status === 'unassembled').length,
      marks: document.querySelectorAll('.mark-unassembled').length,
      value: Number(document.querySelector('#sliders input[data-parameter="c"]').value) }));
  };
  const below = await failedAt(rocker.wholeMin * 0.995), above = await failedAt(rocker.wholeMin * 1.005);
  assert(below.value < rocker.wholeMin && below.unassembled > 0 && below.marks === below.unassembled,
    `four_bar c = ${below.value} mm, below the band (${rocker.wholeMin} mm): ${below.unassembled} rows unassembled, ${below.marks} marked`);
  assert(above.value > rocker.wholeMin && above.unassembled === 0 && above.marks === 0,
    `four_bar c = ${above.value} mm, in the band (from ${rocker.wholeMin} mm): ${above.unassembled} rows unassembled`);
}

// What the samples' constructions showed (each planar sample has polygons; joints-and-links
// ones have centres), checked after all ran.
const constructions = { images: 0, centres: new Set(), solvedImages: 0, solvedCentres: 0 };
const arrowsBeyond = {};  // per sample, at the value its page opens at
const readoutZeros = {};  // per sample, the readout's values of round-off shown as 0 over the run

// A title, description and file name written to run script: shown as text, nothing runs.
async function checkHostile(browser) {
  const hostile = '</script><script>alert(1)</script><img src=x onerror=alert(2)>';
  const dir = path.join(workDir, '</script><script>alert(3)<');
  fs.mkdirSync(dir, { recursive: true });
  const file = path.join(dir, 'script><img src=x onerror=alert(4)>.toml');
  const sample = fs.readFileSync(path.join(samplesDir, 'four_bar.toml'), 'utf8')
    .replace(/^title = .*$/m, 'title = ' + JSON.stringify(hostile) + '\ndescription = ' + JSON.stringify('<b>' + hostile + '</b>'));
  fs.writeFileSync(file, sample);
  const html = path.join(workDir, 'hostile.html');
  run(['page', file, '--sweep', '0:350:10', '-o', html]);
  const { page, seen } = await open(browser, html);
  await scrubTo(page, 3);
  const text = await page.evaluate(() => ({
    title: document.querySelector('h1').textContent,
    paragraphs: Array.from(document.querySelectorAll('header p')).map((p) => p.textContent),
    images: document.querySelectorAll('img, b').length,
    scripts: document.querySelectorAll('script').length,
  }));
  assert.deepStrictEqual(seen.dialogs, [], 'a hostile string ran script');
  assert.strictEqual(text.title, hostile);
  assert.strictEqual(text.paragraphs[0], '<b>' + hostile + '</b>');
  assert.strictEqual(text.paragraphs[1], file);
  assert.strictEqual(text.images, 0, 'a hostile string made elements');
  assert.strictEqual(text.scripts, 2, 'a hostile string made a script element');
  assert.deepStrictEqual(seen.errors, [], 'console errors');
  // A joint's or a link's name is a name (letters, digits, _): a hostile one never reaches
  // a page; the file is refused at its line, and no page is written.
  const joints = fs.readFileSync(path.join(samplesDir, 'example_4_1_joints.toml'), 'utf8');
  for (const [kind, edited] of [
    ['joint', joints.replace(/^B = /m, JSON.stringify(hostile) + ' = ').replace(/"B"\]/g, JSON.stringify(hostile) + ']').replace(/\["B", /g, '[' + JSON.stringify(hostile) + ', ')],
    ['link', joints.replace(/^3 = /m, JSON.stringify(hostile) + ' = ')]]) {
    assert.notStrictEqual(edited, joints, `the ${kind} name was not put into the file`);
    const named = path.join(workDir, `hostile_${kind}.toml`), out = path.join(workDir, `hostile_${kind}.html`);
    fs.writeFileSync(named, edited);
    let refused = null;
    try { run(['page', named, '-o', out]); } catch (e) { refused = e; }
    assert(refused && refused.status !== 0, `a hostile ${kind} name was not refused`);
    assert(new RegExp(`hostile_${kind}\\.toml:[0-9]+: ${kind} name .* is not (a )?valid`).test(String(refused.stderr)),
      `the hostile ${kind} name's message: ${refused.stderr}`);
    assert(!fs.existsSync(out), `a page was written for a hostile ${kind} name`);
  }
}

(async () => {
  const started = Date.now();
  const args = typeof process.getuid === 'function' && process.getuid() === 0 ? ['--no-sandbox'] : [];
  const browser = await chromium.launch({ executablePath: chromiumPath, args: args });
  try {
    // A student's answers file (kinema check's input) is no mechanism.
    const samples = fs.readdirSync(samplesDir).filter((f) => f.endsWith('.toml') && !f.endsWith('_answers.toml')).sort();
    for (const sample of samples) {
      const t = Date.now();
      await checkSample(browser, path.join(samplesDir, sample));
      if (process.env.KINEMA_PAGE_TEST_TIMES) console.log(sample, Date.now() - t);
    }
    await checkFailedRows(browser, path.join(samplesDir, 'problem_4_1_parallelogram.toml'), 'singular');
    await checkFailedRows(browser, path.join(samplesDir, 'triple_rocker_circuit.toml'), 'unassembled');
    await checkFailedRows(browser, path.join(samplesDir, 'piston_driven_crank.toml'), 'unassembled');
    await checkHostile(browser);
    await checkSliders(browser);
    assert(constructions.solvedCentres >= 15, `only ${constructions.solvedCentres} re-solved instant centres checked`);
    assert(constructions.solvedImages >= 20, `only ${constructions.solvedImages} re-solved polygon images checked against eval`);
    assert(constructions.images >= 20, `only ${constructions.images} polygon images checked against eval`);
    assert(arrowsBeyond.piston_driven_crank > 0, 'the piston opened next to its toggle with no arrow stopped at the edge');
    // Problem 4.4's slider F5 moves along y: its relative velocity's x is round-off, read out as 0.
    assert(readoutZeros.problem_4_4_joints > 0, 'problem_4_4_joints: no round-off read out as 0');
    for (const joints of ['problem_4_4_joints', 'crank_shaper', 'example_4_2_joints', 'triple_rocker_circuit'])
      assert(constructions.centres.has(joints), `${joints}: no instant centres shown`);
    console.log(`page: ${samples.length} samples, failed rows and hostile strings checked in chromium in ${Date.now() - started} ms`);
  } finally {
    await browser.close();
  }
})().catch((error) => {
  console.error(error && error.stack ? error.stack : String(error));
  process.exit(1);
});
