// kinema page: the mechanism animated over rows kinema solved (the JSON in #kinema-data,
// written by engine/printers/web/page.cpp): the page draws, plays and reads out the rows.
// Its dimension sliders solve the rows again here, on the model's compiled tape (below).
// Every string of the file is set as text (textContent), never as markup.
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('kinema-data').textContent);
  const SVG = 'http://www.w3.org/2000/svg';
  const rows = data.rows.map(function (line) { return line.split(','); });
  const numbers = rows.map(function (fields) { return fields.map(parseFloat); });
  const drawing = data.drawing;
  // A drawing row is written as [its pattern, its distinct values] (page.cpp): each place's
  // value is the pattern's index among them.
  drawing.rows = drawing.rows.map(function (packed) {
    return packed && drawing.row_patterns[packed[0]].map(function (k) { return packed[1 + k]; });
  });
  const points = data.columns.points;
  const count = rows.length;
  let row = 0;
  let resolved = false;  // the rows are the sliders' (solved here), not the file's

  // Elements, their text always through textContent.
  function node(tag, className, parent, text) {
    const e = document.createElement(tag);
    if (className) e.className = className;
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }
  function svg(tag, attributes, parent, text) {
    const e = document.createElementNS(SVG, tag);
    for (const name in attributes) e.setAttribute(name, attributes[name]);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }
  function status(r) { return rows[r][3]; }
  function fixed(v) { return Math.round(v * 1000) / 1000; }
  // A number for people in `digits` significant digits: from 10^5 up and below 10^-3 as
  // a power of ten ("2×10⁶"; "1000000" and "1.05e+3" were hard to read).
  function readable(v, digits) {
    const rounded = Number(v.toPrecision(digits));
    const a = Math.abs(rounded);
    if (a === 0 || (a >= 1e-3 && a < 1e5)) return String(rounded);
    const power = Math.floor(Math.log10(a));
    const mantissa = Number((rounded / Math.pow(10, power)).toPrecision(digits));
    const superscript = String(power).replace(/-/g, '\u207b').replace(/[0-9]/g, function (d) { return '\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079'[d]; });
    return (mantissa === 1 ? '' : mantissa === -1 ? '-' : mantissa + '\u00d7') + '10' + superscript;
  }
  // A number as kinema's text table writes it (format_significant: %g, 6 significant
  // digits, no trailing zeros, a power of ten below 10^-4 and from 10^6: "1.64625", "1e-05").
  function tableNumber(v) {
    if (v === 0) return '0';
    const parts = v.toExponential(5).split('e');  // rounded first: its power decides the form
    const power = Number(parts[1]);
    if (power < -4 || power >= 6)
      return parts[0].replace(/\.?0+$/, '') + 'e' + (power < 0 ? '-' : '+') + String(Math.abs(power)).padStart(2, '0');
    const text = v.toFixed(5 - power);
    return text.indexOf('.') < 0 ? text : text.replace(/\.?0+$/, '');
  }

  // Header and controls.
  document.title = (data.title || data.file) + ' (kinema page)';
  const header = node('header', '', document.body);
  node('h1', '', header, data.title || data.file);
  if (data.description) node('p', '', header, data.description);
  node('p', '', header, data.file + (data.circuit ? ' (along its circuit through the toggles)' : ''));
  const controls = node('div', 'controls', document.body);
  const play = node('button', '', controls, 'Play');
  play.id = 'play';
  play.title = 'play or pause (space)';
  const back = node('button', '', controls, '\u25c0');
  back.title = 'one value back (left arrow)';
  const forward = node('button', '', controls, '\u25b6');
  forward.title = 'one value on (right arrow)';
  const speedLabel = node('label', '', controls, 'speed ');
  const speed = node('select', '', speedLabel);
  speed.id = 'speed';
  [['values/s: 15', 15], ['values/s: 30', 30], ['values/s: 60', 60], ['values/s: 120', 120]].forEach(function (o) {
    const option = node('option', '', speed, o[0]);
    option.value = o[1];
  });
  speed.value = '30';
  const scrub = node('div', 'scrub', controls);
  const scrubber = node('input', '', scrub);
  scrubber.id = 'scrubber';
  scrubber.type = 'range';
  scrubber.min = 0;
  scrubber.max = Math.max(0, count - 1);
  scrubber.step = 1;
  scrubber.value = 0;
  const marks = svg('svg', { id: 'marks', viewBox: '0 0 1000 8', preserveAspectRatio: 'none' }, scrub);
  function drawMarks() {
    marks.textContent = '';
    for (let r = 0; r < count; ++r) {
      if (status(r) === 'ok') continue;
      const x = count > 1 ? r / (count - 1) * 1000 : 0;
      svg('rect', { x: x - 1.5, y: 0, width: 3, height: 8, class: 'mark-' + status(r), 'data-row': r }, marks);
    }
  }
  drawMarks();
  const value = node('span', 'value', controls);
  value.id = 'value';
  const toggles = {};
  const constructions = data.constructions;
  const hasPolygons = constructions.rows.some(function (c) { return c && c.polygons; });
  const hasCentres = constructions.rows.some(function (c) { return c && c.centres; });
  [['velocity', 'velocity arrows', true], ['acceleration', 'acceleration arrows', true], ['traces', 'paths of points', true],
    ['polygons', 'polygons', hasPolygons], ['centres', 'instant centres', hasCentres]].forEach(function (t) {
    if (!t[2]) return;
    const label = node('label', '', controls);
    const box = node('input', '', label);
    box.type = 'checkbox';
    box.id = 'show-' + t[0];
    box.checked = t[0] !== 'acceleration' && t[0] !== 'centres';
    node('span', '', label, ' ' + t[1]);
    toggles[t[0]] = box;
  });

  // The drawing beside the readout.
  const main = node('main', '', document.body);
  const stage = node('div', 'stage', main);
  const picture = svg('svg', { id: 'mechanism' }, stage);
  const defs = svg('defs', {}, picture);
  const hatch = svg('pattern', { id: 'hatch', width: 6, height: 6, patternUnits: 'userSpaceOnUse',
    patternTransform: 'rotate(45)' }, defs);
  svg('line', { x1: 0, y1: 0, x2: 0, y2: 6, stroke: '#555', 'stroke-width': 1.2 }, hatch);
  ['velocity', 'acceleration'].forEach(function (kind) {
    const marker = svg('marker', { id: 'head-' + kind, viewBox: '0 0 10 10', refX: 9, refY: 5, markerWidth: 7,
      markerHeight: 7, orient: 'auto-start-reverse' }, defs);
    svg('path', { d: 'M0,0 L10,5 L0,10 z', fill: kind === 'velocity' ? '#c62828' : '#2e7d32' }, marker);
  });
  ['polygon', 'centre'].forEach(function (kind) {
    const marker = svg('marker', { id: 'head-' + kind, viewBox: '0 0 10 10', refX: 9, refY: 5, markerWidth: 6,
      markerHeight: 6, orient: 'auto-start-reverse' }, defs);
    svg('path', { d: 'M0,0 L10,5 L0,10 z', fill: kind === 'polygon' ? '#1b1f24' : '#00838f' }, marker);
  });
  const traceLayer = svg('g', { id: 'traces' }, picture);
  const layer = svg('g', { id: 'drawing' }, picture);
  const overlay = svg('g', { id: 'overlay' }, picture);
  const statusBox = node('div', '', stage);
  statusBox.id = 'status';
  const key = node('p', 'key', stage);
  const aside = node('aside', '', main);
  const readout = node('table', '', aside);
  readout.id = 'readout';
  const copy = node('button', '', aside, 'Copy the readout');
  const readoutText = node('textarea', '', aside);
  readoutText.id = 'readout-text';
  readoutText.readOnly = true;
  const sliderArea = node('div', 'sliders', document.body);
  sliderArea.id = 'sliders';
  const polygonArea = node('div', 'polygons', document.body);
  polygonArea.id = 'polygons';
  const plotArea = node('div', 'plots', document.body);

  // The geometry of a row, in the file's length unit: joints (name, x, y), and what to draw.
  function rowGeometry(r) {
    const g = drawing.rows[r];
    if (!g) return null;
    const out = { joints: [], parts: [] };
    if (drawing.form === 'linkage') {
      const at = function (j) { return [g[2 * j], g[2 * j + 1]]; };
      drawing.joint_names.forEach(function (name, j) { out.joints.push({ name: name, at: at(j) }); });
      drawing.guides.forEach(function (guide) { out.parts.push({ kind: 'guide', through: guide.through, along: guide.along }); });
      let block = 2 * drawing.joint_names.length;
      drawing.links.forEach(function (link) {
        const ends = link.joints.map(at);
        if (link.block) out.parts.push({ kind: 'block', at: ends[0], angle: g[block++], label: link.name });
        else out.parts.push({ kind: ends.length >= 3 ? 'plate' : 'bar', ends: ends, label: link.name });
      });
      drawing.pivots.forEach(function (j) { out.parts.push({ kind: 'pivot', at: at(j) }); });
    } else if (drawing.form === 'loops') {
      const numbered = {};
      const ends = [];
      drawing.segments.forEach(function (s, k) {
        const v = g.slice(8 * k, 8 * k + 8);
        const from = [v[0], v[1]], to = [v[2], v[3]];
        if (s.kind === 'ground') {
          out.parts.push({ kind: 'ground', ends: [from, to] });
          if (s.pins[0]) out.parts.push({ kind: 'pivot', at: from });
          if (s.pins[1]) out.parts.push({ kind: 'pivot', at: to });
        } else if (s.kind === 'slider') {
          const angle = Math.atan2(v[7], v[6]);
          if (s.fixed_guide) out.parts.push({ kind: 'guide', through: [v[4], v[5]], along: [v[6], v[7]] });
          else out.parts.push({ kind: 'bar', ends: [from, to], label: null });
          out.parts.push({ kind: 'block', at: [v[4], v[5]], angle: angle, label: s.block_label });
        } else {
          const label = s.link >= 0 && !numbered[s.link] ? drawing.link_labels[s.link] : null;
          if (s.link >= 0) numbered[s.link] = true;
          out.parts.push({ kind: 'bar', ends: [from, to], label: label });
        }
        if (s.pins[0]) ends.push(from);
        if (s.pins[1]) ends.push(to);
      });
      // A point on a link drawn on it, as the worked solution draws it (tikz_mechanism.cpp,
      // draw_segments): a plate with the link's segment from where the point's own vector
      // starts (the four-bar's coupler with P); nothing more for a joint the loops already
      // reach; else a bar.
      const base = 8 * drawing.segments.length;
      const near = function (a, b) { return Math.hypot(a[0] - b[0], a[1] - b[1]) <= 1e-9 * extent.size; };
      drawing.points_on_links.forEach(function (p, k) {
        const from = [g[base + 4 * k], g[base + 4 * k + 1]], at = [g[base + 4 * k + 2], g[base + 4 * k + 3]];
        if (!isFinite(at[0])) return;
        let joint = false, plate = null;
        drawing.segments.forEach(function (s, j) {
          if (s.link !== p.link) return;
          const a = [g[8 * j], g[8 * j + 1]], b = [g[8 * j + 2], g[8 * j + 3]];
          joint = joint || near(a, at) || near(b, at);
          if ((near(a, from) && !near(b, at)) || (near(b, from) && !near(a, at))) plate = [a, b, at];
        });
        if (joint && !plate) return;
        out.parts.push(plate ? { kind: 'plate', ends: plate, label: null } : { kind: 'bar', ends: [from, at], label: null });
      });
      // A loop's joint is named by the point of the file drawn at it, if any.
      const size = extent.size;
      const seen = [];
      ends.forEach(function (e) {
        if (!isFinite(e[0]) || seen.some(function (s) { return Math.hypot(s[0] - e[0], s[1] - e[1]) < 1e-9 * size; })) return;
        seen.push(e);
        let name = '';
        points.forEach(function (p) {
          const x = numbers[r][p.position], y = numbers[r][p.position + 1];
          if (!name && Math.hypot(x - e[0], y - e[1]) < 1e-6 * size) name = p.name;
        });
        // Else the letter the file's lengths give that corner (geometry.hpp lettered_corners).
        (drawing.letters || []).forEach(function (c) {
          const at = g.slice(8 * c.segment + (c.at_to ? 2 : 0), 8 * c.segment + (c.at_to ? 4 : 2));
          if (!name && Math.hypot(at[0] - e[0], at[1] - e[1]) < 1e-6 * size) name = c.letter;
        });
        out.joints.push({ name: name, at: e });
      });
    }
    return out;
  }

  // A spatial chain seen from a direction turned by dragging: the world turned about the
  // motion's centre by yaw (about z, up) and pitch (looking down), projected along the view.
  // It opens at the view the analysis chose (geometry.hpp ChainView, the worked solution's):
  // turned by phi about z, tilted by theta from looking straight down.
  const opening = drawing.view || { theta: 65, phi: 120 };
  const camera = { yaw: -opening.phi * Math.PI / 180, pitch: (90 - opening.theta) * Math.PI / 180, centre: [0, 0, 0] };
  function projectVector(v) {
    const cy = Math.cos(camera.yaw), sy = Math.sin(camera.yaw), cp = Math.cos(camera.pitch), sp = Math.sin(camera.pitch);
    return [cy * v[0] - sy * v[1], cp * v[2] + sp * (sy * v[0] + cy * v[1])];
  }
  function project(p) { return projectVector([p[0] - camera.centre[0], p[1] - camera.centre[1], p[2] - camera.centre[2]]); }
  function chainPoint(n, p) { return [n[p.position], n[p.position + 1], p.dimension === 3 ? n[p.position + 2] : 0]; }

  // The extent of every row's drawing and points: the view fits the whole motion (a chain's:
  // the sphere about its centre that holds it, whichever way it is turned).
  const extent = drawing.form === 'chain' ? (function () {
    const all = [[0, 0, 0]];
    drawing.rows.forEach(function (g) { if (g) for (let k = 0; k + 2 < g.length; k += 12) all.push(g.slice(k, k + 3)); });
    numbers.forEach(function (n) { points.forEach(function (p) { all.push(chainPoint(n, p)); }); });
    const finite = all.filter(function (p) { return p.every(isFinite); });
    const lo = [0, 1, 2].map(function (k) { return Math.min.apply(null, finite.map(function (p) { return p[k]; })); });
    const hi = [0, 1, 2].map(function (k) { return Math.max.apply(null, finite.map(function (p) { return p[k]; })); });
    camera.centre = [0, 1, 2].map(function (k) { return (lo[k] + hi[k]) / 2; });
    const r = Math.max.apply(null, finite.map(function (p) {
      return Math.hypot(p[0] - camera.centre[0], p[1] - camera.centre[1], p[2] - camera.centre[2]);
    })) || 1;
    return { minX: -r, minY: -r, maxX: r, maxY: r, size: 2 * r, cloud: finite };
  })() : (function () {
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
    const add = function (x, y) {
      if (!isFinite(x) || !isFinite(y)) return;
      minX = Math.min(minX, x); maxX = Math.max(maxX, x); minY = Math.min(minY, y); maxY = Math.max(maxY, y);
    };
    // Positions only: a loop segment's last pair is its guide's unit direction; a linkage
    // row ends with its blocks' angles.
    const segmentValues = drawing.form === 'loops' ? 8 * drawing.segments.length : 0;
    drawing.rows.forEach(function (g) {
      if (!g) return;
      const limit = drawing.form === 'linkage' ? 2 * drawing.joint_names.length : g.length;
      for (let k = 0; k + 1 < limit; k += 2) if (k >= segmentValues || k % 8 < 6) add(g[k], g[k + 1]);
    });
    if (!data.spatial) numbers.forEach(function (n) { points.forEach(function (p) { add(n[p.position], n[p.position + 1]); }); });
    if (!isFinite(minX)) { minX = -1; maxX = 1; minY = -1; maxY = 1; }
    return { minX: minX, minY: minY, maxX: maxX, maxY: maxY, size: Math.max(maxX - minX, maxY - minY, 1e-9) };
  })();

  // The view: model (x, y) to pixels (ox + x s, oy - y s); fitted, zoomed by the wheel, panned by dragging.
  const view = { scale: 1, ox: 0, oy: 0 };
  // A chain fitted as seen from the camera's direction at the time (the whole motion's
  // points projected): the sphere that holds it whichever way it is turned left the arm
  // a third of the panel.
  function fitted() {
    if (!extent.cloud) return extent;
    const seen = extent.cloud.map(project);
    const xs = seen.map(function (p) { return p[0]; }), ys = seen.map(function (p) { return p[1]; });
    return { minX: Math.min.apply(null, xs), maxX: Math.max.apply(null, xs), minY: Math.min.apply(null, ys),
      maxY: Math.max.apply(null, ys) };
  }
  function fit() {
    const box = picture.getBoundingClientRect();
    const w = Math.max(box.width, 100), h = Math.max(box.height, 100);
    const e = fitted();
    const sx = (e.maxX - e.minX) || extent.size, sy = (e.maxY - e.minY) || extent.size;
    view.scale = 0.8 * Math.min(w / sx, h / sy);
    view.width = w;
    view.height = h;
    view.ox = w / 2 - view.scale * (e.minX + e.maxX) / 2;
    view.oy = h / 2 + view.scale * (e.minY + e.maxY) / 2;
  }
  function px(p) { return [view.ox + p[0] * view.scale, view.oy - p[1] * view.scale]; }
  function xy(p) { const q = px(p); return fixed(q[0]) + ',' + fixed(q[1]); }
  function line(a, b, className, parent) {
    const p = px(a), q = px(b);
    return svg('line', { x1: p[0], y1: p[1], x2: q[0], y2: q[1], class: className }, parent);
  }

  // Arrows to one scale over the whole run, stated in the key: a point at the run's 95th
  // percentile of magnitudes gets an arrow a fifth of the drawing (near a toggle the rates
  // grow without bound; the largest would shrink every other arrow to nothing).
  function largest(field) {
    const all = [];
    numbers.forEach(function (n) { points.forEach(function (p) { if (isFinite(n[p[field]])) all.push(Math.abs(n[p[field]])); }); });
    all.sort(function (a, b) { return a - b; });
    return all.length ? all[Math.floor(0.95 * (all.length - 1))] : 0;
  }
  const velocityScale = largest('speed') > 0 ? 0.2 * extent.size / largest('speed') : 0;
  const accelerationScale = largest('acceleration') > 0 ? 0.2 * extent.size / largest('acceleration') : 0;

  function drawPart(part, parent) {
    if (part.kind === 'bar') {
      line(part.ends[0], part.ends[1], 'bar-body', parent);
      line(part.ends[0], part.ends[1], 'bar-line', parent);
    } else if (part.kind === 'plate') {
      svg('polygon', { points: part.ends.map(xy).join(' '), class: 'plate' }, parent);
    } else if (part.kind === 'ground') {
      line(part.ends[0], part.ends[1], 'ground-line', parent);
    } else if (part.kind === 'guide') {
      const reach = 0.7 * extent.size;
      const centre = [(extent.minX + extent.maxX) / 2, (extent.minY + extent.maxY) / 2];
      const t = (centre[0] - part.through[0]) * part.along[0] + (centre[1] - part.through[1]) * part.along[1];
      const a = [part.through[0] + part.along[0] * (t - reach), part.through[1] + part.along[1] * (t - reach)];
      const b = [part.through[0] + part.along[0] * (t + reach), part.through[1] + part.along[1] * (t + reach)];
      const p = px(a), q = px(b);
      const angle = Math.atan2(q[1] - p[1], q[0] - p[0]) * 180 / Math.PI;
      svg('rect', { x: p[0], y: p[1] + 1, width: Math.hypot(q[0] - p[0], q[1] - p[1]), height: 8, class: 'hatch',
        transform: 'rotate(' + fixed(angle) + ' ' + fixed(p[0]) + ' ' + fixed(p[1]) + ')' }, parent);
      line(a, b, 'guide', parent);
    } else if (part.kind === 'block') {
      const p = px(part.at);
      svg('rect', { x: p[0] - 16, y: p[1] - 10, width: 32, height: 20, class: 'block',
        transform: 'rotate(' + fixed(-part.angle * 180 / Math.PI) + ' ' + fixed(p[0]) + ' ' + fixed(p[1]) + ')' }, parent);
    } else if (part.kind === 'pivot') {
      const p = px(part.at);
      svg('rect', { x: p[0] - 14, y: p[1] + 12, width: 28, height: 7, class: 'hatch' }, parent);
      svg('line', { x1: p[0] - 14, y1: p[1] + 12, x2: p[0] + 14, y2: p[1] + 12, class: 'guide' }, parent);
      svg('path', { d: 'M' + xy(part.at) + ' l-8,12 l16,0 z', class: 'pivot' }, parent);
    }
  }

  // Link numbers in circles beside each link, and the blocks' numbers above them.
  function drawLinkNumber(part, parent) {
    if (!part.label) return;
    let at;
    if (part.kind === 'block') {
      const p = px(part.at);
      at = [p[0] - 22 * Math.sin(part.angle), p[1] - 22 * Math.cos(part.angle)];
    } else {
      const p = px(part.ends[0]), q = px(part.ends[1]);
      const length = Math.hypot(q[0] - p[0], q[1] - p[1]);
      if (!(length > 1)) return;
      at = [(p[0] + q[0]) / 2 - 16 * (q[1] - p[1]) / length, (p[1] + q[1]) / 2 + 16 * (q[0] - p[0]) / length];
    }
    const g = svg('g', { class: 'link-number', transform: 'translate(' + fixed(at[0]) + ',' + fixed(at[1]) + ')' }, parent);
    svg('circle', { r: 8 }, g);
    svg('text', {}, g, part.label);
    // Where else it may stand (arrangeLabels): either side of the link, nearer either end,
    // then farther out; a block's number on any side of its block.
    g.places = [at];
    if (part.kind === 'block') {
      const p = px(part.at), s = Math.sin(part.angle), c = Math.cos(part.angle);
      [22, 34, 46].forEach(function (r) {
        [[-s, -c], [s, c], [c, -s], [-c, s]].forEach(function (d) { g.places.push([p[0] + r * d[0], p[1] + r * d[1]]); });
      });
    } else {
      const p = px(part.ends[0]), q = px(part.ends[1]), length = Math.hypot(q[0] - p[0], q[1] - p[1]);
      const n = [-(q[1] - p[1]) / length, (q[0] - p[0]) / length];
      [16, 28, 40].forEach(function (out) {
        [0.5, 0.35, 0.65, 0.25, 0.75].forEach(function (f) {
          [out, -out].forEach(function (side) {
            g.places.push([p[0] + f * (q[0] - p[0]) + side * n[0], p[1] + f * (q[1] - p[1]) + side * n[1]]);
          });
        });
      });
    }
  }

  // As the mechanism moves, its labels keep clear of the arrows and of each other: each
  // link number at the first of its places (link's middle first) on no arrow nor number
  // placed before it; then each joint's and point's name at the first of eight places
  // around its mark, else the nearest free one farther out, on no arrow, number, mark or
  // name. The centres' names (drawCentres) then keep off all of these.
  function labelObstacles() {
    const panel = picture.getBoundingClientRect();
    const boxes = [];
    overlay.querySelectorAll('line.velocity, line.acceleration').forEach(function (l) {
      const p = [Number(l.getAttribute('x1')), Number(l.getAttribute('y1'))], q = [Number(l.getAttribute('x2')), Number(l.getAttribute('y2'))];
      if (Math.hypot(q[0] - p[0], q[1] - p[1]) > 0.5) Array.prototype.push.apply(boxes, arrowBoxes(p, q));
    });
    picture.querySelectorAll('circle.joint, circle.point').forEach(function (c) {
      const r = c.getBoundingClientRect();
      boxes.push({ x0: r.left - panel.left, y0: r.top - panel.top, x1: r.right - panel.left, y1: r.bottom - panel.top });
    });
    return boxes;
  }
  function arrangeLabels() {
    const taken = labelObstacles();
    const free = function (b) { return !taken.some(function (o) { return boxesOverlap(b, o); }); };
    picture.querySelectorAll('.link-number').forEach(function (g) {
      const places = g.places || [];
      const box = function (c) { return { x0: c[0] - 9, x1: c[0] + 9, y0: c[1] - 9, y1: c[1] + 9 }; };
      const chosen = places.find(function (c) { return free(box(c)); });
      if (chosen) g.setAttribute('transform', 'translate(' + fixed(chosen[0]) + ',' + fixed(chosen[1]) + ')');
      const m = /translate\(([^,]+),([^)]+)\)/.exec(g.getAttribute('transform'));
      taken.push(box([Number(m[1]), Number(m[2])]));
    });
    picture.querySelectorAll('[data-joint] > text, [data-point] > text').forEach(function (label) {
      const m = /translate\(([^,]+),([^)]+)\)/.exec(label.parentNode.getAttribute('transform'));
      const at = [Number(m[1]), Number(m[2])];
      label.setAttribute('x', 0);  // measured from its mark
      label.setAttribute('y', 0);
      const size = labelSize(label, 'name ' + label.textContent);
      const width = (size.width > 0 ? size.width : 8 * label.textContent.length) + 2, height = size.height > 0 ? size.height + 2 : 17;
      const above = size.height > 0 ? -size.y + 1 : 14;
      const box = function (dx, dy) {
        const x0 = at[0] + dx - 1, y0 = at[1] + dy - above;
        return { dx: dx, dy: dy, x0: x0, x1: x0 + width, y0: y0, y1: y0 + height };
      };
      const around = [[7, -7], [7, 16], [-7 - width, -7], [-7 - width, 16], [9, 4], [-9 - width, 4], [-width / 2, 22], [-width / 2, -10]];
      let chosen = null;
      for (let k = 0; !chosen && k < around.length; ++k) {
        const b = box(around[k][0], around[k][1]);
        if (free(b)) chosen = b;
      }
      for (let k = 1; !chosen && k < 12; ++k) {
        for (let j = 0; !chosen && j < around.length; ++j) {
          const b = box(around[j][0], around[j][1]);
          const cx = (b.x0 + b.x1) / 2 - at[0], cy = (b.y0 + b.y1) / 2 - at[1], d = Math.hypot(cx, cy) || 1;
          const moved = box(around[j][0] + 5 * k * cx / d, around[j][1] + 5 * k * cy / d);
          if (free(moved)) chosen = moved;
        }
      }
      if (!chosen) chosen = box(7, -7);
      label.setAttribute('x', fixed(chosen.dx));
      label.setAttribute('y', fixed(chosen.dy));
      taken.push(chosen);
    });
  }

  // An arrow from a point in the panel whose tip would be beyond it (near a toggle the
  // rates grow without bound) stops at the panel's edge, its magnitude written there:
  // the arrow's scale stays the run's.
  function arrow(from, vector, factor, className, parent, magnitude) {
    if (!(factor > 0) || !isFinite(vector[0]) || Math.hypot(vector[0], vector[1]) === 0) return;
    const tip = [from[0] + vector[0] * factor, from[1] + vector[1] * factor];
    const p = px(from), q = px(tip), margin = 14;
    const lo = [margin, margin], hi = [view.width - margin, view.height - margin];
    const within = function (c) { return c[0] >= lo[0] && c[0] <= hi[0] && c[1] >= lo[1] && c[1] <= hi[1]; };
    if (!within(p) || within(q)) {
      line(from, tip, className, parent).setAttribute('marker-end', 'url(#head-' + className + ')');
      return;
    }
    let t = 1;  // how far along p -> q the panel's edge is
    for (let k = 0; k < 2; ++k) {
      const d = q[k] - p[k];
      if (d > 0) t = Math.min(t, (hi[k] - p[k]) / d);
      if (d < 0) t = Math.min(t, (lo[k] - p[k]) / d);
    }
    const end = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
    const shaft = svg('line', { x1: p[0], y1: p[1], x2: end[0], y2: end[1], class: className + ' beyond',
      'marker-end': 'url(#head-' + className + ')' }, parent);
    shaft.setAttribute('data-beyond', '1');
    const right = end[0] > view.width / 2, below = end[1] > view.height / 2;
    const text = svg('text', { x: fixed(end[0] + (right ? -4 : 4)), class: 'arrow-beyond ' + className + '-beyond',
      'text-anchor': right ? 'end' : 'start' }, parent,
      readable(magnitude, 3) + ' ' + data.length_unit + (className === 'velocity' ? '/s' : '/s^2') + ' (beyond)');
    // Off the magnitudes written before it (two points' arrows leave by the same edge):
    // moved along the edge, inwards, a line at a time.
    const corners = function (t) { const b = t.getBBox(); return { x0: b.x, y0: b.y, x1: b.x + b.width, y1: b.y + b.height }; };
    const before = Array.from(parent.querySelectorAll('text.arrow-beyond')).filter(function (t) { return t !== text; }).map(corners);
    for (let k = 0, y = end[1] + (below ? -6 : 14); k < 50; ++k, y += below ? -13 : 13) {
      text.setAttribute('y', fixed(y));
      const b = corners(text);
      if (!before.some(function (o) { return boxesOverlap(b, o); })) break;
    }
  }

  function message(text, parent) {
    const box = picture.getBoundingClientRect();
    svg('text', { x: box.width / 2, y: box.height / 2, class: 'message' }, parent, text);
  }

  function drawScaleBar(parent) {
    const box = picture.getBoundingClientRect();
    const target = 120 / view.scale;
    const power = Math.pow(10, Math.floor(Math.log10(target)));
    const length = [1, 2, 5, 10].map(function (m) { return m * power; }).filter(function (l) { return l <= target; }).pop() || power;
    const x = 16, y = box.height - 18, w = length * view.scale;
    const bar = svg('g', { id: 'scale-bar', 'data-length': length }, parent);
    svg('path', { d: 'M' + x + ',' + (y - 5) + ' v5 h' + fixed(w) + ' v-5', class: 'scale-bar', fill: 'none' }, bar);
    svg('text', { x: x + w / 2, y: y - 8, class: 'tick', 'text-anchor': 'middle' }, bar, String(length) + ' ' + data.length_unit);
  }

  function drawTraces() {
    traceLayer.textContent = '';
    if (!toggles.traces.checked) return;
    points.forEach(function (p) {
      let path = '', pen = false;
      numbers.forEach(function (n, r) {
        const x = n[p.position], y = n[p.position + 1];
        if (status(r) !== 'ok' || !isFinite(x)) { pen = false; return; }
        path += (pen ? ' L' : ' M') + xy(drawing.form === 'chain' ? project(chainPoint(n, p)) : [x, y]);
        pen = true;
      });
      if (path) svg('path', { d: path, class: 'trace', 'data-point': p.name }, traceLayer);
    });
  }

  function draw() {
    layer.textContent = '';
    overlay.textContent = '';
    picture.setAttribute('data-scale', view.scale);
    picture.setAttribute('data-ox', view.ox);
    picture.setAttribute('data-oy', view.oy);
    const s = status(row);
    picture.setAttribute('data-status', s);
    picture.setAttribute('data-yaw', camera.yaw);
    picture.setAttribute('data-pitch', camera.pitch);
    picture.setAttribute('data-centre', camera.centre.join(','));
    if (drawing.form === 'chain') {
      drawChain(s);
      return;
    }
    const geometry = rowGeometry(row);
    if (!geometry || s === 'unassembled') {
      message('Not assembled at this value: nothing is drawn.', overlay);
      drawScaleBar(overlay);
      return;
    }
    const body = svg('g', { class: s === 'ok' ? '' : 'singular-drawing' }, layer);
    geometry.parts.forEach(function (part) { if (part.kind === 'guide' || part.kind === 'ground') drawPart(part, body); });
    geometry.parts.forEach(function (part) { if (part.kind === 'bar' || part.kind === 'plate') drawPart(part, body); });
    geometry.parts.forEach(function (part) { if (part.kind === 'block' || part.kind === 'pivot') drawPart(part, body); });
    geometry.parts.forEach(function (part) { drawLinkNumber(part, body); });
    geometry.joints.forEach(function (joint) {
      if (!isFinite(joint.at[0])) return;
      const p = px(joint.at);
      const g = svg('g', { class: 'joint-mark', 'data-joint': '', 'data-name': joint.name, 'data-x': joint.at[0],
        'data-y': joint.at[1], transform: 'translate(' + p[0] + ',' + p[1] + ')' }, body);
      svg('circle', { r: 4, class: 'joint' }, g);
      if (joint.name) svg('text', { x: 7, y: -7, class: 'label' }, g, joint.name);
    });
    if (s !== 'ok') return;
    const n = numbers[row];
    points.forEach(function (p) {
      const at = [n[p.position], n[p.position + 1]];
      if (!isFinite(at[0])) return;
      const q = px(at);
      const named = geometry.joints.some(function (j) { return j.name === p.name; });
      const g = svg('g', { 'data-point': p.name, transform: 'translate(' + q[0] + ',' + q[1] + ')' }, overlay);
      svg('circle', { r: 2.5, class: 'point' }, g);
      if (!named) svg('text', { x: 6, y: -6, class: 'label' }, g, p.name);
      if (toggles.velocity.checked) arrow(at, [n[p.velocity], n[p.velocity + 1]], velocityScale, 'velocity', overlay, n[p.speed]);
      if (toggles.acceleration.checked) {
        arrow(at, [n[p.acceleration], n[p.acceleration + 1]], accelerationScale, 'acceleration', overlay, n[p.acceleration + 2]);  // then its magnitude
      }
    });
    arrangeLabels();
    if (toggles.centres && toggles.centres.checked) drawCentres(overlay);
    drawScaleBar(overlay);
  }

  // The constructions of a row (engine/printers/web/page_constructions.cpp): the rows give
  // coordinates, their structures the names, kinds and which points an arrow joins.
  // A row the sliders solved takes the file's row's structure: its images of named points are
  // the row's velocities and accelerations (the tape's); a vertex the analysis placed by
  // its own construction has no value for these dimensions, so it and its arrows are left out.
  function rowPolygons(r) {
    const c = constructions.rows[r];
    if (!c || !c.polygons) return null;
    return c.polygons.map(function (p) {
      const s = constructions.polygon_structures[p[0]];
      let k = 1;
      const next = function () { const q = [p[k], p[k + 1]]; k += 2; return q; };
      const ends = s.vertices.map(function (v) {
        return v.pole ? [0, 0] : v.field !== undefined ? [numbers[r][v.field], numbers[r][v.field + 1]] : next();
      });
      while (k + 1 < p.length) ends.push(next());
      const known = function (j) { return !resolved || (j < s.vertices.length && (s.vertices[j].pole || s.vertices[j].field !== undefined)); };
      const vertices = [], arrows = [];
      s.vertices.forEach(function (v, j) { if (known(j)) vertices.push({ name: v.name, at: ends[j] }); });
      s.arrows.forEach(function (a) {
        if (known(a[2]) && known(a[3])) arrows.push({ kind: a[0], name: a[1], from: ends[a[2]], to: ends[a[3]] });
      });
      return { order: s.order, vertices: vertices, arrows: arrows };
    });
  }
  // A row the sliders solved: its centres from the drawing stage's outputs the analysis reads
  // its own from (engine/symbolic/centre_formulas.hpp), with the file's row's structure and
  // Kennedy lines: each N / (i D), or at infinity across N where the bodies turn alike
  // (instant_centres.cpp centres_from_tape); a pin's at its joint as the row draws it.
  function solvedCentres(r, c) {
    const s = constructions.centre_structures[c.centres[0]];
    const solved = lastSolved && lastSolved[r];
    if (!solved || solved.status !== 'ok' || !solved.drawn || !s.centres.every(function (x) { return x.tape; })) return null;
    const v = solved.drawn, f = R.length_per_unit;
    const out = function (k) { return k < 0 ? 0 : v[k]; };
    let fastest = 0;  // the fastest point: below a 1e-12th of it N is 0 (no centre)
    R.point_dimensions.reduce(function (k, d) {
      fastest = Math.max(fastest, Math.hypot(solved.points[k + d], solved.points[k + d + 1], d === 3 ? solved.points[k + 5] : 0));
      return k + 3 * d;
    }, 0);
    // The fastest-turning body (every body is in a pair): two turn alike within a
    // centre_parallel_tolerance of its angular velocity.
    let turning = 0;
    s.centres.forEach(function (centre) { turning = Math.max(turning, Math.abs(out(centre.tape[2])), Math.abs(out(centre.tape[3]))); });
    const lines = constructions.kennedy_sets[c.centres[1]];
    const g = drawing.rows[r];
    return { not_found: s.not_found, centres: s.centres.map(function (centre, j) {
      // A pin's centre: where this row draws the joint, whatever the bodies' rates.
      if (centre.pin && g) return { name: centre.name, infinite: false, kennedy: lines[j], at: [g[2 * centre.joint], g[2 * centre.joint + 1]] };
      const t = centre.tape, sign = t[1];
      const N = [sign * out(t[0]), sign * out(t[0] + 1)], D = sign * out(t[0] + 2), size = Math.hypot(N[0], N[1]);
      const infinite = Math.abs(D) <= constructions.centre_parallel_tolerance * turning;
      const result = { name: centre.name, infinite: infinite, kennedy: lines[j] };
      if (!infinite) result.at = [N[1] / D / f, -N[0] / D / f];
      else if (size > 1e-12 * fastest) {
        result.direction = [-N[1] / size, N[0] / size];
        result.seen_from = [0, 1].map(function (k) {
          return t[4].reduce(function (sum, p) { return sum + out(p < 0 ? p : p + k); }, 0) / t[4].length / f;
        });
      }
      return result;
    }) };
  }
  function rowCentres(r) {
    const c = constructions.rows[r];
    if (!c || !c.centres) return null;
    if (resolved) return solvedCentres(r, c);
    const s = constructions.centre_structures[c.centres[0]];
    const lines = constructions.kennedy_sets[c.centres[1]];
    const g = drawing.rows[r];
    let k = 2;
    const next = function () { const p = [c.centres[k], c.centres[k + 1]]; k += 2; return p; };
    return { not_found: s.not_found, centres: s.centres.map(function (centre, j) {
      const out = { name: centre.name, infinite: centre.infinite, kennedy: lines[j] };
      if (centre.infinite) out.direction = next();
      else if (centre.joint !== null) out.at = [g[2 * centre.joint], g[2 * centre.joint + 1]];
      else out.at = next();
      if (centre.seen_from) out.seen_from = next();
      return out;
    }) };
  }

  // Labels of points that fall within a few pixels of each other, said once ("o = A").
  // A label's box as drawn, measured once a text (measuring lays the page out again).
  const labelSizes = new Map();
  function labelSize(label, text) {
    if (labelSizes.has(text)) return labelSizes.get(text);
    const b = label.getBBox(), size = { width: b.width, height: b.height, y: b.y };
    if (b.width > 0) labelSizes.set(text, size);
    return size;
  }
  // `taken`: boxes already printed on (x0, y0, x1, y1 in the panel's pixels) that no label may cover.
  function boxesOverlap(a, b) { return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1; }
  // A panel's width as drawn, in pixels (a hidden one: 400): its viewBox is made as wide, so
  // that one unit is a pixel and its text is not stretched.
  function drawnWidth(element) { return Math.max(200, Math.round(element.getBoundingClientRect().width) || 400); }
  function drawLabelled(list, place, parent, className, dataName, separator, taken) {
    const groups = [];
    list.forEach(function (item) {
      const p = place(item.at);
      const group = groups.find(function (g) { return Math.hypot(g.p[0] - p[0], g.p[1] - p[1]) < 4; });
      if (group) group.names.push(item.name);
      else groups.push({ p: p, names: [item.name], item: item });
      const mark = svg('g', { transform: 'translate(' + fixed(p[0]) + ',' + fixed(p[1]) + ')' }, parent);
      mark.setAttribute(dataName, item.name);
      mark.setAttribute('data-x', item.at[0]);
      mark.setAttribute('data-y', item.at[1]);
      svg('circle', { r: 3, class: className }, mark);
    });
    // Each label beside its mark, on no label placed before it: the first free of eight
    // places around the mark, else of the same eight moved out from it step by step (the
    // nearest free place). Its size as drawn (a hidden panel measures nothing: then about
    // 8 px a character of the 13 px text).
    const placed = taken || [];  // the caller's: what is placed here is taken after
    const overlaps = function (b) { return placed.some(function (o) { return boxesOverlap(b, o); }); };
    groups.forEach(function (g) {
      const text = g.names.join(separator);
      const label = svg('text', { x: 0, y: 0, class: 'label' }, parent, text);
      const measured = labelSize(label, text);
      const width = (measured.width > 0 ? measured.width : 8 * text.length) + 2, height = measured.height > 0 ? measured.height + 2 : 17;
      const above = measured.height > 0 ? -measured.y + 1 : 14;  // from the baseline to the box's top
      const box = function (dx, dy) {  // dx, dy: the text's start and baseline from the mark
        const x0 = g.p[0] + dx - 1, y0 = g.p[1] + dy - above;
        return { x: g.p[0] + dx, y: g.p[1] + dy, x0: x0, x1: x0 + width, y0: y0, y1: y0 + height };
      };
      const around = [[6, 14], [6, -6], [-6 - width, 14], [-6 - width, -6], [8, 4], [-8 - width, 4], [-width / 2, 22], [-width / 2, -10]];
      let chosen = null;
      for (let k = 0; !chosen && k < around.length; ++k) {
        const b = box(around[k][0], around[k][1]);
        if (!overlaps(b)) chosen = b;
      }
      for (let k = 1; !chosen; ++k) {
        for (let j = 0; !chosen && j < around.length; ++j) {
          const b = box(around[j][0], around[j][1]);
          const cx = (b.x0 + b.x1) / 2 - g.p[0], cy = (b.y0 + b.y1) / 2 - g.p[1], d = Math.hypot(cx, cy) || 1;
          const moved = box(around[j][0] + 5 * k * cx / d, around[j][1] + 5 * k * cy / d);
          if (!overlaps(moved)) chosen = moved;
        }
      }
      placed.push(chosen);
      label.setAttribute('x', fixed(chosen.x));
      label.setAttribute('y', fixed(chosen.y));
    });
  }

  // The velocity and the acceleration polygon, each in a panel of its own, drawn as the
  // notes draw them: at a round scale (1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 units a pixel times a power of ten)
  // that fits the row's polygon into the panel as wide as it is drawn, stated under it.
  const polygonPanels = (function () {
    if (!hasPolygons) return [];
    return [['velocity polygon', '/s'], ['acceleration polygon', '/s^2']].map(function (kind, k) {
      const box = node('div', 'polygon', polygonArea);
      node('h2', '', box, kind[0]);
      const panel = svg('svg', { viewBox: '0 0 400 260', id: k === 0 ? 'velocity-polygon' : 'acceleration-polygon' }, box);
      return { svg: panel, key: node('p', 'key', box), unit: data.length_unit + kind[1], order: k };
    });
  })();
  // A panel `width` by 260 units (pixels): the polygon within 30 of the sides, 20 of the
  // top and 40 of the bottom (the scale bar's).
  function roundScale(polygon, width) {
    const xs = polygon.vertices.map(function (v) { return v.at[0]; }), ys = polygon.vertices.map(function (v) { return v.at[1]; });
    const box = { x0: Math.min.apply(null, xs), x1: Math.max.apply(null, xs), y0: Math.min.apply(null, ys), y1: Math.max.apply(null, ys) };
    const perPixel = Math.max((box.x1 - box.x0) / (width - 60), (box.y1 - box.y0) / 200, 1e-300);
    const power = Math.pow(10, Math.floor(Math.log10(perPixel)));
    const step = [1, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10].map(function (m) { return m * power; }).find(function (m) { return m >= perPixel * (1 - 1e-12); });
    return { perPixel: step, cx: width / 2 - (box.x0 + box.x1) / 2 / step, cy: 120 + (box.y0 + box.y1) / 2 / step };
  }
  // Boxes a polygon's labels keep off: each arrow's head (its marker, about 10 px long and
  // 6 wide at the tip) and its shaft, sampled.
  function arrowBoxes(p, q) {
    const length = Math.hypot(q[0] - p[0], q[1] - p[1]), u = [(q[0] - p[0]) / length, (q[1] - p[1]) / length];
    const boxes = [];
    const around = function (c, r) { boxes.push({ x0: c[0] - r, x1: c[0] + r, y0: c[1] - r, y1: c[1] + r }); };
    for (let d = 0; d < Math.min(10, length); d += 2) around([q[0] - u[0] * d, q[1] - u[1] * d], 4);
    for (let d = 10; d < length; d += 4) around([q[0] - u[0] * d, q[1] - u[1] * d], 1.5);
    return boxes;
  }
  // Arrows shorter than this (px) are drawn without a head.
  const kPolygonHeadless = 14;
  // An arrow's name as the notes write it: "an_BA" is a with n above and BA below.
  function arrowName(name, parent, attributes) {
    const text = svg('text', attributes, parent);
    const cut = name.indexOf('_');
    const head = cut < 0 ? name : name.slice(0, cut), tail = cut < 0 ? '' : name.slice(cut + 1);
    text.appendChild(document.createTextNode(head.charAt(0)));
    if (head.length > 1) svg('tspan', { 'baseline-shift': 'super', 'font-size': '9px' }, text, head.slice(1));
    if (tail) svg('tspan', { 'baseline-shift': 'sub', 'font-size': '9px' }, text, tail);
    return text;
  }
  // Each arrow of 20 px or more named beside its middle, on no arrow, head or name placed
  // before it: the nearer side first, then farther out.
  function labelArrows(arrows, parent, taken) {
    arrows.forEach(function (d) {
      if (d.length < 20) return;
      const u = [(d.q[0] - d.p[0]) / d.length, (d.q[1] - d.p[1]) / d.length], n = [-u[1], u[0]];
      const middle = [(d.p[0] + d.q[0]) / 2, (d.p[1] + d.q[1]) / 2];
      const label = arrowName(d.arrow.name, parent, { x: 0, y: 0, class: 'label polygon-label', 'data-arrow-label': d.arrow.name });
      const measured = labelSize(label, 'arrow ' + d.arrow.name);
      const width = (measured.width > 0 ? measured.width : 7 * d.arrow.name.length) + 2, height = measured.height > 0 ? measured.height + 2 : 17;
      let chosen = null;
      for (let out = 10; !chosen && out <= 60; out += 6) {
        for (const side of [1, -1]) {
          for (const along of [0, -0.25, 0.25]) {
            const c = [middle[0] + side * n[0] * (out + width / 2) + u[0] * along * d.length,
                       middle[1] + side * n[1] * (out + height / 2) + u[1] * along * d.length];
            const box = { x0: c[0] - width / 2, x1: c[0] + width / 2, y0: c[1] - height / 2, y1: c[1] + height / 2 };
            if (!chosen && !taken.some(function (o) { return boxesOverlap(box, o); })) chosen = box;
          }
        }
      }
      if (!chosen) { parent.removeChild(label); return; }  // no room: the legend and the vertices name it
      taken.push(chosen);
      label.setAttribute('x', fixed(chosen.x0 + 1));
      label.setAttribute('y', fixed(measured.height > 0 ? chosen.y0 + 1 - measured.y : chosen.y1 - 4));
    });
  }
  // What each line's colour and dash mean, for the kinds this polygon has.
  function polygonLegend(key, kinds, order) {
    const words = { absolute: order === 0 ? 'absolute velocity' : 'absolute acceleration', relative: 'relative (turning)',
      sliding: 'relative (sliding)', normal: 'normal (\u03c9\u00b2r)', tangential: 'tangential (\u03b1r)', coriolis: 'Coriolis (2\u03c9v)' };
    kinds.forEach(function (kind) {
      const entry = node('span', 'legend-entry', key);
      entry.setAttribute('data-legend', kind);
      const swatch = svg('svg', { width: 26, height: 8 }, entry);
      svg('line', { x1: 1, y1: 4, x2: 25, y2: 4, class: 'polygon-arrow polygon-' + kind }, swatch);
      entry.appendChild(document.createTextNode(' ' + words[kind] + '  '));
    });
  }
  function drawPolygons() {
    const shown = toggles.polygons && toggles.polygons.checked;
    polygonArea.style.display = shown ? '' : 'none';
    if (!shown) return;
    const polygons = status(row) === 'ok' ? rowPolygons(row) : null;
    polygonPanels.forEach(function (panel) {
      panel.svg.textContent = '';
      const width = drawnWidth(panel.svg);
      panel.svg.setAttribute('viewBox', '0 0 ' + width + ' 260');
      if (!polygons) {
        panel.key.textContent = '';
        svg('text', { x: width / 2, y: 130, class: 'message' }, panel.svg, 'No polygon at this value.');
        return;
      }
      const polygon = polygons[panel.order];
      const scale = roundScale(polygon, width);
      panel.svg.setAttribute('data-per-pixel', scale.perPixel);
      // A scale bar of 50 units of the panel (a round length).
      const bar = 50 * scale.perPixel;
      svg('path', { d: 'M12,242 v5 h50 v-5', class: 'scale-bar', fill: 'none' }, panel.svg);
      svg('text', { x: 70, y: 248, class: 'tick' }, panel.svg, readable(bar, 3) + ' ' + panel.unit);
      panel.key.textContent = '';
      const place = function (p) { return [scale.cx + p[0] / scale.perPixel, scale.cy - p[1] / scale.perPixel]; };
      const taken = [], drawnArrows = [], kinds = [];
      polygon.arrows.forEach(function (a) {
        const p = place(a.from), q = place(a.to);
        const length = Math.hypot(q[0] - p[0], q[1] - p[1]);
        if (length < 0.5) return;
        // A head only on an arrow longer than one and a half heads: the heads of short
        // arrows between close vertices piled up over each other.
        const attributes = { x1: fixed(p[0]), y1: fixed(p[1]), x2: fixed(q[0]), y2: fixed(q[1]), class: 'polygon-arrow polygon-' + a.kind };
        if (length >= kPolygonHeadless) attributes['marker-end'] = 'url(#head-polygon)';
        const arrowLine = svg('line', attributes, panel.svg);
        arrowLine.setAttribute('data-arrow', a.name);
        Array.prototype.push.apply(taken, arrowBoxes(p, q));
        drawnArrows.push({ arrow: a, p: p, q: q, length: length });
        if (kinds.indexOf(a.kind) < 0) kinds.push(a.kind);
      });
      labelArrows(drawnArrows, panel.svg, taken);
      drawLabelled(polygon.vertices, place, panel.svg, 'point', 'data-vertex', ' = ', taken);
      polygonLegend(panel.key, kinds, panel.order);
    });
  }

  // Instant centres over the drawing: Kennedy lines (dashed) through the three centres
  // each joins, a centre at infinity as an arrow from where it is seen toward it.
  function drawCentres(parent) {
    const found = rowCentres(row);
    if (!found) return;
    const g = svg('g', { id: 'centres' }, parent);
    const finite = found.centres.filter(function (c) { return c.at; });
    finite.forEach(function (centre) {
      centre.kennedy.forEach(function (pair) {
        const ends = [centre.at];
        pair.forEach(function (k) { if (k !== null && found.centres[k].at) ends.push(found.centres[k].at); });
        let a = ends[0], b = ends[0], far = 0;
        ends.forEach(function (p) {
          ends.forEach(function (q) {
            const d = Math.hypot(p[0] - q[0], p[1] - q[1]);
            if (d > far) { far = d; a = p; b = q; }
          });
        });
        if (far > 0) line(a, b, 'kennedy', g);
      });
    });
    // The joints' letters, the links' numbers and the arrows stay readable under the centres' names.
    const panel = picture.getBoundingClientRect();
    const taken = Array.from(picture.querySelectorAll('[data-joint] text, [data-point] text, .link-number')).map(function (t) {
      const r = t.getBoundingClientRect();
      return { x0: r.left - panel.left, y0: r.top - panel.top, x1: r.right - panel.left, y1: r.bottom - panel.top };
    }).filter(function (b) { return b.x1 > b.x0; }).concat(labelObstacles());
    // A name set at the first of `places` (its text's start and baseline) on nothing taken,
    // else at the first; taken from then on.
    const setFree = function (text, given) {
      // Then farther out from the first, in eight directions, step by step.
      const places = given.slice();
      for (let k = 1; k <= 10; ++k)
        for (let a = 0; a < 8; ++a) places.push([given[0][0] + 7 * k * Math.cos(a * Math.PI / 4), given[0][1] + 7 * k * Math.sin(a * Math.PI / 4)]);
      let chosen = null;
      for (let k = 0; k < places.length && !chosen; ++k) {
        text.setAttribute('x', fixed(places[k][0]));
        text.setAttribute('y', fixed(places[k][1]));
        const b = text.getBBox(), box = { x0: b.x, y0: b.y, x1: b.x + b.width, y1: b.y + b.height };
        if (!taken.some(function (o) { return boxesOverlap(box, o); })) chosen = box;
      }
      if (!chosen) {
        text.setAttribute('x', fixed(places[0][0]));
        text.setAttribute('y', fixed(places[0][1]));
        const b = text.getBBox();
        chosen = { x0: b.x, y0: b.y, x1: b.x + b.width, y1: b.y + b.height };
      }
      taken.push(chosen);
    };
    // A centre at infinity: an arrow from the slider it belongs to, named beside its tip.
    found.centres.forEach(function (centre) {
      if (!centre.infinite || !centre.seen_from) return;
      const p = px(centre.seen_from);
      const q = [p[0] + 60 * centre.direction[0], p[1] - 60 * centre.direction[1]];
      svg('line', { x1: fixed(p[0]), y1: fixed(p[1]), x2: fixed(q[0]), y2: fixed(q[1]), class: 'centre-infinite',
        'marker-end': 'url(#head-centre)' }, g).setAttribute('data-centre', centre.name);
      const text = svg('text', { class: 'label centre-label' }, g, centre.name + ' \u221e');
      setFree(text, [[q[0] + 4, q[1] - 4], [q[0] + 4, q[1] + 14], [q[0] - 44, q[1] - 4], [q[0] - 44, q[1] + 14], [q[0] + 8, q[1] + 28], [q[0] - 44, q[1] + 28]]);
    });
    // Names on the centres' marks (drawLabelled adds what it places to taken).
    drawLabelled(finite, px, g, 'centre', 'data-centre', ', ', taken);
    // A centre beyond the panel (the triple rocker's I02): an arrow at the panel's edge
    // towards it, with its name.
    const box = picture.getBoundingClientRect(), inset = 30;
    const middle = [box.width / 2, box.height / 2];
    finite.forEach(function (centre) {
      const p = px(centre.at);
      if (p[0] >= 0 && p[0] <= box.width && p[1] >= 0 && p[1] <= box.height) return;
      const d = [p[0] - middle[0], p[1] - middle[1]], length = Math.hypot(d[0], d[1]);
      const reach = Math.min((middle[0] - inset) / Math.abs(d[0] / length || 1e-12), (middle[1] - inset) / Math.abs(d[1] / length || 1e-12));
      const tip = [middle[0] + d[0] / length * reach, middle[1] + d[1] / length * reach];
      const tail = [tip[0] - 40 * d[0] / length, tip[1] - 40 * d[1] / length];
      svg('line', { x1: fixed(tail[0]), y1: fixed(tail[1]), x2: fixed(tip[0]), y2: fixed(tip[1]), class: 'centre-infinite',
        'marker-end': 'url(#head-centre)', 'data-centre-beyond': centre.name }, g);
      const text = svg('text', { class: 'label centre-label' }, g, centre.name);
      const x = tail[0] - (d[0] > 0 ? 30 : -4), y = tail[1] + (d[1] > 0 ? -6 : 14);
      setFree(text, [[x, y], [x, y + (d[1] > 0 ? -14 : 14)], [x + (d[0] > 0 ? -30 : 30), y], [x, y + (d[1] > 0 ? -28 : 28)]]);
    });
  }

  // A spatial chain: the observer's axes at the origin, each frame's origin joined to its
  // parent's and its triad (x red, y green, z blue), the points with their arrows.
  function drawChain(s) {
    const g = drawing.rows[row];
    if (!g || !g.length || s === 'unassembled') {
      message('Not assembled at this value: nothing is drawn.', overlay);
      return;
    }
    const body = svg('g', { class: s === 'ok' ? '' : 'singular-drawing' }, layer);
    const axisLength = 0.2 * extent.size, triad = 0.08 * extent.size;
    ['x', 'y', 'z'].forEach(function (name, k) {
      const tip = [0, 0, 0];
      tip[k] = axisLength;
      line(project([0, 0, 0]), project(tip), 'world-axis', body);
      const q = px(project(tip));
      svg('text', { x: fixed(q[0] + 4), y: fixed(q[1] - 4), class: 'tick' }, body, name);
    });
    const origin = function (name) {
      const k = drawing.frames.indexOf(name);
      return k < 0 ? [0, 0, 0] : g.slice(12 * k, 12 * k + 3);
    };
    // The bodies (geometry.hpp ChainBodies): each point on a bar from its frame's origin,
    // each distance closure the coupler between its two points, each frame on its parent's
    // body or, its parent being the observer, on a ground pivot.
    const n = numbers[row];
    const placed = function (p) { const at = chainPoint(n, p); return at.every(isFinite) ? at : null; };
    const apart = function (a, b) { return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) > 1e-9 * extent.size; };
    if (n) {
      points.forEach(function (p, i) {
        const frame = drawing.point_frames[i], at = placed(p);
        if (frame && at && apart(origin(frame), at)) drawPart({ kind: 'bar', ends: [project(origin(frame)), project(at)] }, body);
      });
      drawing.couplers.forEach(function (ends) {
        const a = placed(points[ends[0]]), b = placed(points[ends[1]]);
        if (!a || !b) return;
        const bar = svg('g', { 'data-coupler': points[ends[0]].name + points[ends[1]].name }, body);
        drawPart({ kind: 'bar', ends: [project(a), project(b)] }, bar);
      });
    }
    drawing.frames.forEach(function (name, k) {
      const o = g.slice(12 * k, 12 * k + 3);
      if (drawing.ground_frames[k]) drawPart({ kind: 'pivot', at: project(o) }, body);
      else if (apart(origin(drawing.parents[k]), o)) drawPart({ kind: 'bar', ends: [project(origin(drawing.parents[k])), project(o)] }, body);
      ['x', 'y', 'z'].forEach(function (axis, a) {
        const d = g.slice(12 * k + 3 + 3 * a, 12 * k + 6 + 3 * a);
        line(project(o), project([o[0] + triad * d[0], o[1] + triad * d[1], o[2] + triad * d[2]]), 'triad-' + axis, body);
      });
      const q = px(project(o));
      const mark = svg('g', { 'data-frame': name, transform: 'translate(' + fixed(q[0]) + ',' + fixed(q[1]) + ')' }, body);
      svg('circle', { r: 3, class: 'joint' }, mark);
      const letter = drawing.frame_joints[k];
      if (letter) svg('text', { x: 7, y: -7, class: 'label', 'data-joint-letter': letter }, mark, letter);
      // Beside a ground pivot's hatching, not on it.
      svg('text', drawing.ground_frames[k] ? { x: 17, y: 18, class: 'label frame-label' } : { x: -8, y: 16, class: 'label frame-label' },
        mark, name);
    });
    if (s !== 'ok') return;
    points.forEach(function (p) {
      const at = placed(p);
      if (!at) return;
      const flat = project(at), q = px(flat);
      const mark = svg('g', { 'data-point': p.name, 'data-x': at[0], 'data-y': at[1], 'data-z': at[2],
        transform: 'translate(' + q[0] + ',' + q[1] + ')' }, overlay);
      svg('circle', { r: 3, class: 'point' }, mark);
      svg('text', { x: 6, y: -6, class: 'label' }, mark, p.name);
      const d = p.dimension;
      const vector = function (k) { return projectVector([n[k], n[k + 1], d === 3 ? n[k + 2] : 0]); };
      if (toggles.velocity.checked) arrow(flat, vector(p.velocity), velocityScale, 'velocity', overlay, n[p.speed]);
      if (toggles.acceleration.checked) {
        arrow(flat, vector(p.acceleration), accelerationScale, 'acceleration', overlay, n[p.acceleration + d]);
      }
    });
    drawScaleBar(overlay);
  }

  function showKey() {
    let text = drawing.form === 'chain' ? 'Drag to turn (shift-drag to pan), wheel to zoom, double-click to fit. Frames: x red, y green, z blue.'
      : 'Drag to pan, wheel to zoom, double-click to fit.';
    const unit = data.length_unit;
    if (velocityScale > 0) text += ' Velocity arrows (red): 1 ' + unit + ' of drawing = ' + readable(1 / velocityScale, 3) + ' ' + unit + '/s.';
    if (accelerationScale > 0) {
      text += ' Acceleration arrows (green, dashed): 1 ' + unit + ' = ' + readable(1 / accelerationScale, 3) + ' ' + unit + '/s^2.';
    }
    key.textContent = text;
  }

  // The readout: every field of the row, in the text table's digits (tableNumber), each
  // value zero at its scale as kinema's views show it (zero_at_scale, engine/base/number_format):
  // below data.round_off of the larger of the problem's size for the field's kind (kinema
  // writes it) and the field's largest magnitude over the run, it is 0. Each cell holds the
  // full value as kinema eval --format csv writes it (data-value, its title), and that is
  // what is copied (the button, the text box, or cells selected and copied).
  const readoutCells = data.columns.fields.map(function (field) {
    const tr = node('tr', '', readout);
    node('th', '', tr, field.name + (field.unit ? ' [' + field.unit + ']' : ''));
    return node('td', '', tr);
  });
  let readoutScales = [];
  function measureReadout() {  // again when the sliders solve new rows
    readoutScales = data.columns.fields.map(function (field, k) {
      let largest = field.size || 0;
      numbers.forEach(function (n) { if (isFinite(n[k])) largest = Math.max(largest, Math.abs(n[k])); });
      return largest;
    });
  }
  measureReadout();
  // Row r's fields for people ("shown": a number in the table's digits, zero at its scale;
  // text as it is) and as kinema wrote them ("full").
  function readoutOf(r) {
    return data.columns.fields.map(function (field, k) {
      const full = rows[r][k] === undefined ? '' : rows[r][k];
      const v = numbers[r][k];
      if (full === '' || typeof field.size !== 'number' || !isFinite(v)) return { shown: full, full: full };
      return { shown: tableNumber(Math.abs(v) < data.round_off * readoutScales[k] ? 0 : v), full: full };
    });
  }
  function readoutLine(k, full) {
    const f = data.columns.fields[k];
    return f.name + (f.unit ? ' [' + f.unit + ']' : '') + '\t' + full + '\n';
  }
  function showReadout() {
    const fields = readoutOf(row);
    let text = '';
    readoutCells.forEach(function (cell, k) {
      cell.textContent = fields[k].shown;
      cell.setAttribute('data-value', fields[k].full);
      cell.title = fields[k].full;
      text += readoutLine(k, fields[k].full);
    });
    readoutText.value = text;
    const s = status(row);
    statusBox.className = s === 'ok' ? '' : s;
    statusBox.textContent = s === 'ok' ? '' : (s === 'singular' ? 'Singular: ' : 'Not assembled: ') + data.reasons[row];
    value.textContent = data.input.name + ' = ' + fields[0].shown + ' ' + data.input.unit + '  (' + (row + 1) + ' of ' + count + ')';
  }
  copy.addEventListener('click', function () {
    readoutText.select();
    if (navigator.clipboard) navigator.clipboard.writeText(readoutText.value).catch(function () {});
  });
  // Cells selected in the readout copy as their full values, a line a field.
  readout.addEventListener('copy', function (event) {
    const selection = window.getSelection();
    let text = '';
    readoutCells.forEach(function (cell, k) {
      if (selection.containsNode(cell.parentNode, true)) text += readoutLine(k, cell.getAttribute('data-value'));
    });
    if (!text) return;
    event.clipboardData.setData('text/plain', text);
    event.preventDefault();
  });

  // Plots of rates, second rates and point speeds against the input (along a circuit:
  // against the row, the input going back and forth); a cursor at the row; a click moves there.
  const colours = ['#1c3f94', '#c62828', '#2e7d32', '#d98b00', '#8e44ad', '#00838f', '#6d4c41', '#ad1457'];
  let plots = [];
  // Round ticks over [lo, hi] drawn `length` px long, as the worked solution's plots take
  // them (engine/printers/latex/pgfplots.cpp, axis_ticks): the smallest step of 1, 2, 2.5 or
  // 5 times a power of ten (a turn's degrees at 45, 90 or 180) at which neighbouring labels
  // stand `gap(a, b)` px apart at least.
  function roundTicks(lo, hi, length, gap, turn) {
    const range = hi - lo, perPx = range / length;
    if (!(range > 0) || !isFinite(range)) return [lo];
    const mantissas = turn ? [45, 90, 180] : [1, 2, 2.5, 5];
    for (let decade = turn ? 1 : Math.pow(10, Math.floor(Math.log10(range)) - 3); decade < 1e300; decade *= 10) {
      for (let m = 0; m < mantissas.length; ++m) {
        const step = mantissas[m] * decade, ticks = [];
        for (let k = Math.ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step && ticks.length < 50; ++k) ticks.push(k === 0 ? 0 : k * step);
        if (ticks.length >= 50) continue;
        let fits = true;
        for (let i = 1; i < ticks.length && fits; ++i) fits = (ticks[i] - ticks[i - 1]) / perPx >= gap(ticks[i - 1], ticks[i]);
        if (fits) return ticks.length ? ticks : [lo];
      }
    }
    return [lo, hi];
  }
  // A tick's label in as many digits as its step needs (2.5 steps one more): 102.5, not 103.
  function tickText(v, ticks) {
    const step = ticks.length > 1 ? Math.abs(ticks[1] - ticks[0]) : Math.abs(v) || 1;
    if (Math.abs(v) <= 1e-9 * step) return '0';
    const extra = Math.abs(step / Math.pow(10, Math.floor(Math.log10(step) + 1e-9)) - 2.5) < 1e-6 ? 1 : 0;
    const largest = Math.max.apply(null, ticks.map(Math.abs));
    if (largest < 1e5 && step >= 1e-3) return v.toFixed(Math.max(0, Math.ceil(-Math.log10(step) - 1e-9) + extra));
    return readable(v, Math.max(1, Math.floor(Math.log10(Math.abs(v)) + 1e-9) - Math.floor(Math.log10(step) + 1e-9) + 1 + extra));
  }
  // A label's width in the chart's units: measured where the page is laid out, else
  // estimated from its characters (10 px text).
  function labelWidth(text) {
    const measured = text.getComputedTextLength ? text.getComputedTextLength() : 0;
    return measured > 0 ? measured : 6.5 * text.textContent.length;
  }
  // Made again when the sliders solve new rows.
  function buildPlots() {
    plotArea.textContent = '';
    // Every chart placed before any is measured: each one added narrows those before it.
    const shown = data.columns.plots.filter(function (p) { return p.fields.length > 0; }).map(function (plot) {
      const box = node('div', 'plot', plotArea);
      node('h2', '', box, plot.title + (data.circuit ? ' along the circuit' : ' against ' + data.input.name));
      return { plot: plot, chart: svg('svg', { class: 'chart' }, box), legend: node('div', 'legend', box) };
    });
    plots = shown.map(function (placed) {
      const plot = placed.plot, chart = placed.chart, legend = placed.legend;
      const W = drawnWidth(chart);
      chart.setAttribute('viewBox', '0 0 ' + W + ' 200');
      const xs = numbers.map(function (n, r) { return data.circuit ? r : n[0]; });
      let lo = Infinity, hi = -Infinity;
      plot.fields.forEach(function (f) { numbers.forEach(function (n) { if (isFinite(n[f])) { lo = Math.min(lo, n[f]); hi = Math.max(hi, n[f]); } }); });
      if (!isFinite(lo)) { lo = -1; hi = 1; }
      if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 1; hi += 1; }
      const x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs);
      // Round ticks up the side, 22 px apart at least (a label's height and a gap); their
      // labels first: the left margin is as wide as the widest of them, so a long one is
      // not cut by the chart's edge.
      const Y = function (y) { return 182 - (y - lo) / (hi - lo) * 172; };
      const yTicks = roundTicks(lo, hi, 172, function () { return 22; }, false);
      const yLabels = yTicks.map(function (v) {
        return svg('text', { y: fixed(Y(v) + 3.5), class: 'tick', 'text-anchor': 'end' }, chart, tickText(v, yTicks));
      });
      const left = Math.max(40, 8 + Math.max.apply(null, yLabels.map(labelWidth)));
      const X = function (x) { return left + (x - x0) / ((x1 - x0) || 1) * (W - 10 - left); };
      yTicks.forEach(function (v, k) {
        yLabels[k].setAttribute('x', left - 4);
        svg('line', { x1: left - 3, y1: fixed(Y(v)), x2: left, y2: fixed(Y(v)), class: 'axis' }, chart);
      });
      svg('line', { x1: left, y1: 182, x2: W - 10, y2: 182, class: 'axis' }, chart);
      svg('line', { x1: left, y1: 10, x2: left, y2: 182, class: 'axis' }, chart);
      if (lo < 0 && hi > 0) svg('line', { x1: left, y1: Y(0), x2: W - 10, y2: Y(0), class: 'axis' }, chart);
      // Round ticks of the input under the axis (along a circuit: of the rows, counted from
      // 1), each label clear of the next by 12 px; the unit after the last.
      const xFrom = data.circuit ? 1 : x0, xTo = data.circuit ? count : x1;
      const turn = !data.circuit && data.input.unit === 'deg' && xTo - xFrom >= 180;
      const xTicks = roundTicks(xFrom, xTo, W - 10 - left, function (a, b) {
        return 12 + 3.25 * (tickText(a, [a, b]).length + tickText(b, [a, b]).length);
      }, turn).filter(function (v) { return !data.circuit || v === Math.round(v); });
      const xText = function (v) { return data.circuit ? String(Math.round(v)) : tickText(v, xTicks); };
      xTicks.forEach(function (v, k) {
        const at = X(data.circuit ? v - 1 : v);
        svg('line', { x1: fixed(at), y1: 182, x2: fixed(at), y2: 185, class: 'axis' }, chart);
        const anchor = xTicks.length > 1 && k === xTicks.length - 1 && at > W - 40 ? 'end' : 'middle';
        svg('text', { x: fixed(anchor === 'end' ? Math.min(at + 4, W - 2) : at), y: 196, class: 'tick', 'text-anchor': anchor }, chart,
            xText(v) + (k === xTicks.length - 1 ? ' ' + (data.circuit ? '(row)' : data.input.unit) : ''));
      });
      plot.fields.forEach(function (f, k) {
        let path = '', pen = false;
        numbers.forEach(function (n, r) {
          if (!isFinite(n[f])) { pen = false; return; }
          path += (pen ? ' L' : ' M') + fixed(X(xs[r])) + ',' + fixed(Y(n[f]));
          pen = true;
        });
        const colour = colours[k % colours.length];
        if (path) svg('path', { d: path, fill: 'none', stroke: colour, 'stroke-width': 1.3, 'vector-effect': 'non-scaling-stroke' }, chart);
        const field = data.columns.fields[f];
        node('span', '', legend, '\u25a0 ' + field.name + ' [' + field.unit + ']').style.color = colour;
      });
      const cursor = svg('line', { y1: 10, y2: 182, class: 'cursor', 'vector-effect': 'non-scaling-stroke' }, chart);
      chart.addEventListener('click', function (event) {
        const b = chart.getBoundingClientRect();
        const x = x0 + ((event.clientX - b.left) / b.width * W - left) / (W - 10 - left) * ((x1 - x0) || 1);
        let best = 0;
        xs.forEach(function (v, r) { if (Math.abs(v - x) < Math.abs(xs[best] - x)) best = r; });
        setRow(best);
      });
      return { cursor: cursor, x: function () { return X(xs[row]); } };
    });
  }
  buildPlots();

  function moveCursors() {
    plots.forEach(function (p) { p.cursor.setAttribute('x1', p.x()); p.cursor.setAttribute('x2', p.x()); });
  }

  function setRow(r) {
    row = Math.max(0, Math.min(count - 1, r));
    scrubber.value = row;
    showReadout();
    moveCursors();
    draw();
    drawPolygons();
  }

  // Playing: rows at the chosen rate, looping; frame times kept for measuring.
  let playing = false, last = 0, carry = 0;
  const frameTimes = [], drawTimes = [];
  function frame(time) {
    if (!playing) return;
    if (last) {
      frameTimes.push(time - last);
      if (frameTimes.length > 600) frameTimes.shift();
      carry += (time - last) / 1000 * Number(speed.value);
      const steps = Math.floor(carry);
      carry -= steps;
      if (steps > 0) {
        const begun = performance.now();
        setRow((row + steps) % count);
        drawTimes.push(performance.now() - begun);
        if (drawTimes.length > 600) drawTimes.shift();
      }
    }
    last = time;
    requestAnimationFrame(frame);
  }
  function setPlaying(on) {
    playing = on && count > 1;
    play.textContent = playing ? 'Pause' : 'Play';
    last = 0;
    if (playing) requestAnimationFrame(frame);
  }
  play.addEventListener('click', function () { setPlaying(!playing); });
  back.addEventListener('click', function () { setRow(row - 1); });
  forward.addEventListener('click', function () { setRow(row + 1); });
  scrubber.addEventListener('input', function () { setRow(Number(scrubber.value)); });
  Object.keys(toggles).forEach(function (k) {
    toggles[k].addEventListener('change', function () { drawTraces(); draw(); drawPolygons(); });
  });
  document.addEventListener('keydown', function (event) {
    if (event.target && (event.target.tagName === 'TEXTAREA' || event.target.tagName === 'SELECT')) return;
    const moves = { ArrowRight: row + 1, ArrowLeft: row - 1, Home: 0, End: count - 1 };
    if (event.key === ' ') setPlaying(!playing);
    else if (event.key in moves) setRow(moves[event.key]);
    else return;
    event.preventDefault();
  });

  // Zoom about the pointer; pan by dragging.
  picture.addEventListener('wheel', function (event) {
    event.preventDefault();
    const b = picture.getBoundingClientRect();
    const mx = event.clientX - b.left, my = event.clientY - b.top;
    const factor = Math.exp(-event.deltaY * 0.0015);
    view.ox = mx - (mx - view.ox) * factor;
    view.oy = my - (my - view.oy) * factor;
    view.scale *= factor;
    drawTraces();
    draw();
  }, { passive: false });
  let drag = null;
  picture.addEventListener('pointerdown', function (event) {
    drag = { x: event.clientX, y: event.clientY };
    picture.setPointerCapture(event.pointerId);
  });
  picture.addEventListener('pointermove', function (event) {
    if (!drag) return;
    if (drawing.form === 'chain' && !event.shiftKey) {  // a chain turns (shift-drag pans)
      camera.yaw += (event.clientX - drag.x) * 0.01;
      camera.pitch = Math.max(-1.5, Math.min(1.5, camera.pitch + (event.clientY - drag.y) * 0.01));
    } else {
      view.ox += event.clientX - drag.x;
      view.oy += event.clientY - drag.y;
    }
    drag = { x: event.clientX, y: event.clientY };
    drawTraces();
    draw();
  });
  picture.addEventListener('pointerup', function () { drag = null; });
  picture.addEventListener('dblclick', function () { fit(); drawTraces(); draw(); });
  window.addEventListener('resize', function () {
    fit(); drawTraces(); draw();
    buildPlots(); drawPolygons();
    moveCursors();
  });


  // Dimension sliders: the mechanism solved again in the page for other values of the
  // file's parameters. The model's compiled tape (data.resolve.tape, parameters among its
  // inputs) runs on kinemaTapeRunner, generated by kinema from its one op table; Newton,
  // continuation and the singularity test follow kinema's (engine/numeric/workspace.cpp,
  // sweep.cpp, solver.hpp, whose constants come with the data), so a row solved here is
  // kinema eval's for the file edited to these dimensions.
  function tapeOf(t) {
    const m = t.code.length / 6;
    const tape = { op: new Int32Array(m), out: new Int32Array(m), a: new Int32Array(m), b: new Int32Array(m),
      c: new Int32Array(m), e: new Int32Array(m), registers: Float64Array.from(t.registers, function (v) { return v === null ? NaN : v; }),
      stageEnd: t.stage_end, levelBegin: t.level_begin, outputs: t.outputs };
    for (let k = 0; k < m; ++k) {
      tape.op[k] = t.code[6 * k]; tape.out[k] = t.code[6 * k + 1]; tape.a[k] = t.code[6 * k + 2];
      tape.b[k] = t.code[6 * k + 3]; tape.c[k] = t.code[6 * k + 4]; tape.e[k] = t.code[6 * k + 5];
    }
    return tape;
  }

  // solver.hpp's LU with partial pivoting (row-major n x n, in place) and its solve.
  function luFactor(a, pivots, n) {
    for (let c = 0; c < n; ++c) {
      let best = c;
      for (let r = c + 1; r < n; ++r) if (Math.abs(a[r * n + c]) > Math.abs(a[best * n + c])) best = r;
      pivots[c] = best;
      if (best !== c) for (let j = 0; j < n; ++j) { const t = a[c * n + j]; a[c * n + j] = a[best * n + j]; a[best * n + j] = t; }
      const pivot = a[c * n + c];
      if (pivot === 0) continue;
      for (let r = c + 1; r < n; ++r) {
        const factor = a[r * n + c] /= pivot;
        for (let j = c + 1; j < n; ++j) a[r * n + j] -= factor * a[c * n + j];
      }
    }
  }
  function luSolve(a, inversePivots, pivots, x, n) {
    for (let c = 0; c < n; ++c) if (pivots[c] !== c) { const t = x[c]; x[c] = x[pivots[c]]; x[pivots[c]] = t; }
    for (let c = 0; c < n; ++c) for (let r = c + 1; r < n; ++r) x[r] -= a[r * n + c] * x[c];
    for (let c = n; c-- > 0;) {
      x[c] *= inversePivots[c];
      for (let r = 0; r < c; ++r) x[r] -= a[r * n + c] * x[c];
    }
  }
  // solver.hpp's lu_determinant_sign: a step whose ends differ in it passed a singular position.
  function luDeterminantSign(a, pivots, n) {
    let sign = 1;
    for (let c = 0; c < n; ++c) {
      const pivot = a[c * n + c];
      if (!(Math.abs(pivot) > 0) || !isFinite(pivot)) return 0;
      if (pivot < 0) sign = -sign;
      if (pivots[c] !== c) sign = -sign;
    }
    return sign;
  }
  // std::remainder(x, 2 pi): the short way round a turn.
  function remainderTurn(x) {
    const turn = 2 * Math.PI, k = x / turn;
    let m = Math.round(k);
    if (Math.abs(k - Math.trunc(k)) === 0.5) m = 2 * Math.round(k / 2);
    return x - turn * m;
  }
  function pivotRatio(a, n, lengthScale) {
    let smallest = Infinity, largest = n === 1 ? lengthScale : 0;
    for (let c = 0; c < n; ++c) {
      const pivot = Math.abs(a[c * n + c]);
      smallest = Math.min(smallest, pivot);
      largest = Math.max(largest, pivot);
    }
    const ratio = smallest / largest;
    return isFinite(ratio) ? ratio : 0;
  }
  // One-sided Jacobi (solver.hpp jacobi_orthogonalise), with v when given.
  function jacobi(a, v, n, K) {
    if (v) for (let i = 0; i < n; ++i) for (let j = 0; j < n; ++j) v[i * n + j] = i === j ? 1 : 0;
    for (let sweep = 0; sweep < K.jacobi_sweeps; ++sweep) {
      let rotated = false;
      for (let p = 0; p + 1 < n; ++p) {
        for (let q = p + 1; q < n; ++q) {
          let alpha = 0, beta = 0, gamma = 0;
          for (let i = 0; i < n; ++i) {
            alpha += a[i * n + p] * a[i * n + p]; beta += a[i * n + q] * a[i * n + q]; gamma += a[i * n + p] * a[i * n + q];
          }
          if (!(Math.abs(gamma) > K.jacobi_tolerance * Math.sqrt(alpha) * Math.sqrt(beta))) continue;
          rotated = true;
          const zeta = (beta - alpha) / (2 * gamma);
          const t = (zeta >= 0 ? 1 : -1) / (Math.abs(zeta) + Math.hypot(1, zeta));
          const c = 1 / Math.sqrt(1 + t * t), s = c * t;
          for (let i = 0; i < n; ++i) {
            const ap = a[i * n + p], aq = a[i * n + q];
            a[i * n + p] = c * ap - s * aq; a[i * n + q] = s * ap + c * aq;
          }
          if (v) for (let i = 0; i < n; ++i) {
            const vp = v[i * n + p], vq = v[i * n + q];
            v[i * n + p] = c * vp - s * vq; v[i * n + q] = s * vp + c * vq;
          }
        }
      }
      if (!rotated) break;
    }
  }
  function columnLength(a, j, n) {
    let sum = 0;
    for (let i = 0; i < n; ++i) sum += a[i * n + j] * a[i * n + j];
    return Math.sqrt(sum);
  }

  function makeSolver(R) {
    const K = R.constants, tape = tapeOf(R.tape), formulas = tapeOf(R.formulas), run = kinemaTapeRunner.run;
    const n = R.guess.length, P = R.parameter_count, r = Float64Array.from(tape.registers);
    const at = { input: P, rate: P + 1, second: P + 2, q: P + 3, qd: P + 3 + n, qdd: P + 3 + 2 * n };
    const end = tape.stageEnd, out = tape.outputs, level = tape.levelBegin;
    const inputLevel = R.input_level, coordinateLevel = R.coordinate_level;
    const lu = new Float64Array(n * n), inversePivots = new Float64Array(n), pivots = new Int32Array(n);
    // Buffers reused from value to value (a sweep allocates only its rows).
    const newtonTrial = new Float64Array(n), newtonStep = new Float64Array(n), corrected = new Float64Array(n);
    const solver = { n: n, columnScale: new Float64Array(n), lengthScale: 1, maxStep: R.max_step };
    const lengthScaleOf = function (values) {
      let largest = 0;
      R.parameters.forEach(function (p, k) { if (p.sets_length_scale) largest = Math.max(largest, Math.abs(values[k])); });
      return largest > 0 ? largest : 1;
    };
    const fileLengthScale = lengthScaleOf(R.parameters.map(function (p) { return p.value; }));
    // The sliders' values (SI, by parameter index); the formula parameters follow them.
    solver.setParameters = function (values) {
      const f = Float64Array.from(formulas.registers);
      for (let p = 0; p < P; ++p) f[p] = values[p];
      run(formulas, f, 0, formulas.stageEnd[0]);
      const all = values.slice();
      R.formula_targets.forEach(function (p, k) { all[p] = f[formulas.outputs[0][k]]; });
      for (let p = 0; p < P; ++p) r[p] = all[p];
      // What depends on the parameters alone runs once (CompiledExpressions::prepare).
      for (let s = 0; s < end.length; ++s) run(tape, r, level[s][0], level[s][1]);
      evaluatedInput = NaN;
      solver.lengthScale = lengthScaleOf(all);
      for (let i = 0; i < n; ++i) solver.columnScale[i] = R.length_unknowns[i] ? solver.lengthScale : 1;
      solver.maxStep = R.max_step_follows_length ? R.max_step * solver.lengthScale / fileLengthScale : R.max_step;
      return all;
    };
    let evaluatedInput = NaN;
    const evaluated = new Float64Array(n);
    // Only q changed (a Newton iterate): what depends on the input alone still holds.
    function evaluatePosition(input, q) {
      const from = evaluatedInput === input ? coordinateLevel : inputLevel;
      r[at.input] = input;
      for (let i = 0; i < n; ++i) r[at.q + i] = q[i];
      run(tape, r, level[0][from], end[0]);
      evaluatedInput = input;
      evaluated.set(q);
    }
    function evaluatedAt(input, q) {
      if (evaluatedInput !== input) return false;
      for (let i = 0; i < n; ++i) if (evaluated[i] !== q[i]) return false;
      return true;
    }
    const phi = function (i) { return r[out[0][i]]; };
    const phiQ = function (i, j) { return r[out[0][n + j * n + i]]; };
    const phiTheta = function (i) { return r[out[0][n + n * n + i]]; };
    function residualNorm() {
      let norm = 0;
      for (let i = 0; i < n; ++i) {
        const m = Math.abs(phi(i));
        if (isNaN(m)) return m;
        norm = Math.max(norm, m);
      }
      return norm;
    }
    function scaledJacobian(a) {
      for (let i = 0; i < n; ++i) for (let j = 0; j < n; ++j) a[i * n + j] = phiQ(i, j) * solver.columnScale[j];
      return a;
    }
    function factorise() {
      scaledJacobian(lu);
      luFactor(lu, pivots, n);
      for (let c = 0; c < n; ++c) inversePivots[c] = 1 / lu[c * n + c];
    }
    function reciprocalCondition() {
      const ratio = pivotRatio(lu, n, solver.lengthScale);
      if (ratio === 0) return 0;
      if (ratio >= K.clearly_regular_pivot_ratio || n === 1) return ratio;
      const a = scaledJacobian(new Float64Array(n * n));
      jacobi(a, null, n, K);
      let smallest = Infinity, largest = 0;
      for (let j = 0; j < n; ++j) { const l = columnLength(a, j, n); smallest = Math.min(smallest, l); largest = Math.max(largest, l); }
      const rc = smallest / largest;
      return isFinite(rc) ? rc : 0;
    }
    function solveRhs(x) {
      luSolve(lu, inversePivots, pivots, x, n);
      for (let i = 0; i < n; ++i) x[i] *= solver.columnScale[i];
      return x;
    }
    function leastSquaresStep(b) {
      const a = new Float64Array(n * n), v = new Float64Array(n * n), x = new Float64Array(n);
      for (let i = 0; i < n; ++i) for (let j = 0; j < n; ++j) a[i * n + j] = phiQ(i, j);
      jacobi(a, v, n, K);
      let largest = 0;
      for (let j = 0; j < n; ++j) largest = Math.max(largest, columnLength(a, j, n));
      const cutoff = n * K.epsilon * largest;
      for (let j = 0; j < n; ++j) {
        const sigma = columnLength(a, j, n);
        if (!(sigma > cutoff)) continue;
        let projection = 0;
        for (let i = 0; i < n; ++i) projection += a[i * n + j] * b[i];
        const coefficient = projection / (sigma * sigma);
        for (let i = 0; i < n; ++i) x[i] += v[i * n + j] * coefficient;
      }
      return x;
    }
    const outputsOf = function (stage) {
      const registers = out[stage], values = new Float64Array(registers.length);
      for (let k = 0; k < registers.length; ++k) values[k] = r[registers[k]];
      return values;
    };
    const allFinite = function (v) { for (let i = 0; i < v.length; ++i) if (!isFinite(v[i])) return false; return true; };
    // Workspace::solve_position: Newton with step halving; q (a Float64Array) updated in place.
    function solvePosition(input, q) {
      const tolerance = K.newton_tolerance * solver.lengthScale;
      if (!evaluatedAt(input, q)) evaluatePosition(input, q);
      let norm = residualNorm(), converged = false;
      const trial = newtonTrial;
      for (let iteration = 0; iteration < K.newton_iterations && isFinite(norm); ++iteration) {
        if (norm <= tolerance) { converged = true; break; }
        factorise();
        let step = newtonStep;
        if (pivotRatio(lu, n, solver.lengthScale) > K.least_squares_pivot_ratio) {
          for (let i = 0; i < n; ++i) step[i] = -phi(i);
          solveRhs(step);
        } else {
          const b = new Float64Array(n);
          for (let i = 0; i < n; ++i) b[i] = -phi(i);
          step = leastSquaresStep(b);
        }
        if (!allFinite(step)) break;
        let lambda = 1, improved = false;
        for (let halving = 0; halving < K.step_halvings; ++halving, lambda *= 0.5) {
          for (let i = 0; i < n; ++i) trial[i] = q[i] + lambda * step[i];
          evaluatePosition(input, trial);
          const trialNorm = residualNorm();
          if (isFinite(trialNorm) && trialNorm < norm) { improved = true; norm = trialNorm; q.set(trial); break; }
        }
        if (!improved) break;
      }
      if (!converged && norm <= K.rounding_tolerance * solver.lengthScale) converged = true;
      if (!evaluatedAt(input, q)) evaluatePosition(input, q);
      return converged && allFinite(q);
    }
    function sensitivity(input, q) {
      if (!evaluatedAt(input, q)) evaluatePosition(input, q);
      factorise();
      if (reciprocalCondition() < K.singular_threshold) return null;
      const dq = new Float64Array(n);
      for (let i = 0; i < n; ++i) dq[i] = -phiTheta(i);
      solveRhs(dq);
      return allFinite(dq) ? dq : null;
    }
    function jacobianSign(input, q) {
      if (!evaluatedAt(input, q)) evaluatePosition(input, q);
      factorise();
      return luDeterminantSign(lu, pivots, n);
    }
    // Workspace::predict_and_correct: Newton from the prediction, refused on another branch
    // or past a toggle; q holds the position the step starts from (at `from`, sign fromSign).
    let changePointsPassed = 0;  // Workspace::change_points_passed
    function predictAndCorrect(from, to, predicted, q, fromSign) {
      const trial = corrected;
      trial.set(predicted);
      if (!solvePosition(to, trial)) return false;
      let correction = 0, step = K.least_step * Math.abs(to - from) / solver.maxStep;
      for (let i = 0; i < n; ++i) {
        const off = Math.abs(trial[i] - predicted[i]) / solver.columnScale[i];
        if (!(off <= K.branch_tolerance)) return false;
        correction = Math.max(correction, off);
        step = Math.max(step, Math.abs(predicted[i] - q[i]) / solver.columnScale[i]);
      }
      const toSign = jacobianSign(to, trial);
      // Landed on a singular position (the motion's own toggle or change point): a branch
      // ending there corrects as much as it steps, and its sign says nothing.
      if (reciprocalCondition() < K.singular_threshold) { q.set(trial); return true; }
      if (!(correction <= K.step_correction * step)) return false;
      if (toSign !== fromSign) {
        if (!changePointBetween(from, q, fromSign, to, Float64Array.from(trial), toSign)) return false;
        ++changePointsPassed;
      }
      q.set(trial);
      return true;
    }
    // Workspace::change_point_between: the sign changes at one input without a jump.
    function changePointBetween(from, fromQ, fromSign, to, toQ, toSign) {
      if (fromSign === 0 || toSign === 0) return false;
      let lo = from, hi = to, loQ = Float64Array.from(fromQ), hiQ = toQ;
      const width = K.crossing_width * solver.maxStep;
      while (Math.abs(hi - lo) > width) {
        const mid = 0.5 * (lo + hi);
        if (mid === lo || mid === hi) break;
        const midQ = new Float64Array(n);
        for (let i = 0; i < n; ++i) midQ[i] = 0.5 * (loQ[i] + hiQ[i]);
        // Closing at Newton's stall level is not enough: inside a narrow gap the loop misses by less.
        if (!solvePosition(mid, midQ) || !(residualNorm() <= K.crossing_residual * solver.lengthScale)) return false;
        if (jacobianSign(mid, midQ) === fromSign) { lo = mid; loQ = midQ; } else { hi = mid; hiQ = midQ; }
      }
      const largestJump = K.crossing_jump * Math.abs(hi - lo) / solver.maxStep;
      for (let i = 0; i < n; ++i) if (!(Math.abs(hiQ[i] - loQ[i]) / solver.columnScale[i] <= largestJump)) return false;
      return true;
    }
    // Workspace::continue_to: small predicted steps, halved where refused.
    function continueTo(from, to, q) {
      const maxStep = solver.maxStep, minStep = maxStep * 1e-7;
      if (!(Math.abs(to - from) <= K.max_continuation_steps * maxStep)) return false;
      let t = from, h = Math.sign(to - from) * Math.min(maxStep, Math.abs(to - from));
      const predicted = new Float64Array(n);
      let regular = null;
      while (t !== to) {
        if (Math.abs(to - t) <= Math.abs(h) * (1 + 1e-12)) h = to - t;
        if (t + h === t) return false;
        const slope = sensitivity(t, q);
        let accepted = false;
        if (slope) {
          const sign = luDeterminantSign(lu, pivots, n);
          regular = { input: t, q: Float64Array.from(q), slope: slope, sign: sign };
          for (let i = 0; i < n; ++i) predicted[i] = q[i] + slope[i] * h;
          accepted = predictAndCorrect(t, t + h, predicted, q, sign);
        } else if (regular) {
          // A step landed on a singular position (a change point): from the last regular one, over it.
          for (let i = 0; i < n; ++i) predicted[i] = regular.q[i] + regular.slope[i] * (t + h - regular.input);
          const restart = Float64Array.from(regular.q);
          accepted = predictAndCorrect(regular.input, t + h, predicted, restart, regular.sign);
          if (accepted) q.set(restart);
        }
        if (accepted) {
          t = h === to - t ? to : t + h;
          h = Math.sign(to - from) * Math.min(maxStep, 2 * Math.abs(h));
        } else {
          h /= 2;
          if (Math.abs(h) < minStep) return false;
        }
      }
      return true;
    }
    // Workspace::motion_into: rates, second rates, points and the drawing stage's values.
    function motion(input, q) {
      const row = { input: input, status: 'ok', q: Float64Array.from(q) };
      if (!evaluatedAt(input, q)) evaluatePosition(input, q);
      factorise();
      if (reciprocalCondition() < K.singular_threshold) {
        // Drawn all the same (a position without rates, as Kinematics::drawing_values draws it).
        row.status = 'singular';
        row.why = 'jacobian';
        for (let i = 0; i < n; ++i) { r[at.qd + i] = NaN; r[at.qdd + i] = NaN; }
        for (let s = 1; s < end.length; ++s) run(tape, r, level[s][inputLevel], end[s]);
        row.drawn = outputsOf(3);
        return row;
      }
      const qd = new Float64Array(n);
      for (let i = 0; i < n; ++i) qd[i] = -phiTheta(i) * R.rate;
      solveRhs(qd);
      r[at.rate] = R.rate;
      r[at.second] = R.second_rate;
      for (let i = 0; i < n; ++i) r[at.qd + i] = qd[i];
      run(tape, r, level[1][inputLevel], end[1]);
      const qdd = new Float64Array(n);
      for (let i = 0; i < n; ++i) qdd[i] = r[out[1][i]];
      solveRhs(qdd);
      for (let i = 0; i < n; ++i) r[at.qdd + i] = qdd[i];
      run(tape, r, level[2][inputLevel], end[2]);
      run(tape, r, level[3][inputLevel], end[3]);
      row.qd = qd;
      row.qdd = qdd;
      row.points = outputsOf(2);
      row.drawn = outputsOf(3);
      if (!allFinite(qd) || !allFinite(qdd) || !allFinite(row.points)) { row.status = 'singular'; row.why = 'rates'; }
      return row;
    }
    // sweep.cpp's FileAssembly: the guesses' position at their own input value, carried
    // each way along the input in steps of the largest continuation step from there.
    function fileAssembly() {
      let started = false, homeOk = false, home = R.guess_input;
      const ways = [];
      function start() {
        if (started) return homeOk;
        started = true;
        let q = null;
        // Guesses that do not close at their own value, or close on a singular position: the
        // nearest value they close at on a regular one.
        const regularAt = function (input) {
          q = Float64Array.from(R.guess);
          return solvePosition(input, q) && sensitivity(input, q) !== null;
        };
        homeOk = regularAt(home);
        for (let k = 1; !homeOk && k <= K.home_search_steps; ++k) {
          for (const side of [1, -1]) {
            if (regularAt(R.guess_input + side * k * solver.maxStep)) { home = R.guess_input + side * k * solver.maxStep; homeOk = true; break; }
          }
        }
        for (let w = 0; w < 2; ++w) ways.push({ inputs: [home], q: [Float64Array.from(q)], stopped: false, crossedAt: Infinity });
        return homeOk;
      }
      function extend(way, ahead) {
        while (Math.abs(way.inputs[way.inputs.length - 1] - home) < Math.abs(ahead)) {
          if (way.stopped) return false;
          const from = way.inputs[way.inputs.length - 1];
          const to = home + Math.sign(ahead) * way.inputs.length * solver.maxStep;
          const q = Float64Array.from(way.q[way.q.length - 1]);
          const passed = changePointsPassed;
          let on = continueTo(from, to, q);
          if (!on && way.q.length >= 2) {
            // The last position kept is singular (a change point on a step's end): from the one before.
            q.set(way.q[way.q.length - 2]);
            on = continueTo(way.inputs[way.inputs.length - 2], to, q);
          }
          if (!on) { way.stopped = true; return false; }
          if (changePointsPassed !== passed) way.crossedAt = Math.min(way.crossedAt, way.inputs.length);
          way.inputs.push(to);
          way.q.push(q);
        }
        return true;
      }
      // The position at `input` into q: { ok }, and whether the value was too far to carry.
      // The short way round, unless only the long way reaches it without a change point.
      function reach(input, q) {
        const result = { ok: false, tooFar: false };
        if (!start()) return result;
        let ahead = input - home;
        if (R.periodic_input) ahead = remainderTurn(ahead);
        const tries = [ahead, ahead - Math.sign(ahead) * 2 * Math.PI];
        const count = R.periodic_input && ahead !== 0 ? 2 : 1;
        for (let w = 0; w < count; ++w) {
          const target = home + tries[w], way = ways[tries[w] < 0 ? 1 : 0];
          if (!(Math.abs(tries[w]) <= K.most_entry_steps * solver.maxStep)) { if (w === 0) result.tooFar = true; continue; }
          // Where the way stops before the target, it may still reach it.
          extend(way, tries[w]);
          let k = 0;
          while (k + 1 < way.inputs.length && Math.abs(way.inputs[k + 1] - home) <= Math.abs(tries[w])) ++k;
          const p = Float64Array.from(way.q[k]);
          const passed = changePointsPassed;
          if (!continueTo(way.inputs[k], target, p)) continue;
          if (target !== input && !solvePosition(input, p)) continue;
          const crossed = way.crossedAt <= k || changePointsPassed !== passed;
          if (crossed && result.ok) continue;  // the short way's, kept
          q.set(p);
          result.ok = true;
          if (!crossed) return result;
        }
        return result;
      }
      return { hasHome: start, reach: reach };
    }
    // The sweep over the page's inputs (sweep.cpp solve_rows, one value at a time): each row
    // continued from the last (the short way round a periodic angle), a row without one
    // before it (the first, one past a gap) the file's assembly carried from its guesses.
    solver.sweep = function (inputs) {
      const rows = [];
      const assembly = fileAssembly();
      let q = Float64Array.from(R.guess), havePrevious = false, qSingular = false, lastOk = null, sign = 0;
      const predicted = new Float64Array(n);
      inputs.forEach(function (input, k) {
        let solved = false;
        const trial = Float64Array.from(q);
        if (havePrevious) {
          const before = rows[k - 1], h = input - before.input;
          if (R.rate !== 0 && Math.abs(h) <= solver.maxStep) {
            predict(before, h, predicted);
            if (sign === 0) sign = jacobianSign(before.input, q);
            solved = predictAndCorrect(before.input, input, predicted, trial, sign);
          }
          if (!solved) {
            trial.set(q);
            const target = R.periodic_input ? before.input + remainderTurn(h) : input;
            solved = continueTo(before.input, target, trial) && (target === input || solvePosition(input, trial));
            if (!solved) solved = assembly.reach(input, trial).ok;
          }
        } else {
          let fromHome = false;
          if (assembly.hasHome()) {
            const reached = assembly.reach(input, trial);
            fromHome = reached.ok || !reached.tooFar;
            solved = reached.ok;
          }
          if (!fromHome) {
            trial.set(q);
            solved = solvePosition(input, trial);
            if (!solved && qSingular && lastOk && R.rate !== 0) {
              predict(lastOk, input - lastOk.input, trial);
              solved = solvePosition(input, trial);
            }
          }
        }
        if (!solved) {
          rows.push({ input: input, status: 'unassembled' });
          havePrevious = false;
          return;
        }
        q = trial;
        const row = motion(input, q);
        sign = luDeterminantSign(lu, pivots, n);
        qSingular = row.status === 'singular';
        havePrevious = row.status === 'ok';
        if (havePrevious) lastOk = row;
        rows.push(row);
      });
      return rows;
    };
    function predict(row, h, into) {
      const rate = R.rate, second = R.second_rate;
      for (let i = 0; i < n; ++i) {
        const slope = row.qd[i] / rate, curvature = (row.qdd[i] - slope * second) / (rate * rate);
        into[i] = row.q[i] + h * (slope + 0.5 * h * curvature);
      }
    }
    return solver;
  }

  // The sliders: one for each parameter the file writes as a length or an angle, over the
  // range the analysis found (engine/analysis/slider_ranges: where the mechanism assembles at
  // one value of the run at least, a band on the track where it runs through every one); the
  // file's other parameters follow through their formulas. A move solves every row of the page again (the
  // same input values) and redraws whatever the page draws from rows.
  const R = data.resolve;
  const solver = R ? makeSolver(R) : null;
  const fileRows = { rows: rows.slice(), numbers: numbers.slice(), drawing: drawing.rows.slice(), reasons: data.reasons.slice(),
    guides: drawing.guides };
  const sliders = [];
  const resolveTimes = [];
  let lastSolved = null;
  function outputValue(p, si) { return p.dimension === 'angle' ? si * 180 / Math.PI : si / R.length_per_unit; }
  function siValue(p, shown) { return p.dimension === 'angle' ? shown * Math.PI / 180 : shown * R.length_per_unit; }
  function unitOf(p) { return p.dimension === 'angle' ? 'deg' : R.length_unit; }
  // OutputScale (engine/constraints/output_columns.cpp): the CSV's units, angles wrapped to (-180, 180].
  function remainder360(d) {
    const k = d / 360;
    let m = Math.round(k);
    if (Math.abs(k - Math.trunc(k)) === 0.5) m = 2 * Math.round(k / 2);
    return d - 360 * m;
  }
  function coordinateOut(dimension, si) {
    if (dimension === 'time') return si;
    if (dimension !== 'angle') return si / R.length_per_unit;
    let d = si * 180 / Math.PI;
    if (d > -180 && d <= 180) return d;
    d = remainder360(d);
    return d <= -180 ? d + 360 : d;
  }
  function unwrappedOut(dimension, si) { return dimension === 'time' ? si : dimension === 'angle' ? si * 180 / Math.PI : si / R.length_per_unit; }
  function rateOut(dimension, si) { return dimension === 'angle' || dimension === 'time' ? si : si / R.length_per_unit; }
  function lengthOf(v, k, d) {
    const squares = v[k] * v[k] + v[k + 1] * v[k + 1] + (d === 3 ? v[k + 2] * v[k + 2] : 0);
    if (squares > 1e-300 && squares < 1e300) return Math.sqrt(squares);
    return Math.hypot(v[k], v[k + 1], d === 3 ? v[k + 2] : 0);
  }
  // A solved row as the CSV's fields (numbers in its units; NaN where the status leaves none).
  function fieldsOf(solved) {
    const f = R.length_per_unit, out = [unwrappedOut(R.input_dimension, solved.input),
      rateOut(R.input_dimension, R.rate), rateOut(R.input_dimension, R.second_rate), solved.status];
    R.unknowns.forEach(function (dimension, i) {
      const ok = solved.status === 'ok';
      out.push(solved.status === 'unassembled' ? NaN : coordinateOut(dimension, solved.q[i]));
      out.push(ok ? rateOut(dimension, solved.qd[i]) : NaN, ok ? rateOut(dimension, solved.qdd[i]) : NaN);
    });
    let k = 0;
    R.point_dimensions.forEach(function (d) {
      const v = solved.status === 'ok' ? solved.points : null;
      const value = function (j) { return v ? v[j] / f : NaN; };
      for (let c = 0; c < d; ++c) out.push(value(k + c));
      for (let c = 0; c < d; ++c) out.push(value(k + d + c));
      out.push(v ? lengthOf(v, k + d, d) / f : NaN);
      for (let c = 0; c < d; ++c) out.push(value(k + 2 * d + c));
      out.push(v ? lengthOf(v, k + 2 * d, d) / f : NaN);
      k += 3 * d;
    });
    // A chain's frames: angular velocity and acceleration, after the points on the same stage.
    for (let c = 0; c < 6 * R.frame_count; ++c) out.push(solved.status === 'ok' ? solved.points[k + c] : NaN);
    // Joints and links: the blocks', sliders', guide points' and relative turnings' columns,
    // from the drawing stage (kinematics.cpp linkage_stage).
    if (R.linkage) R.linkage.column_kinds.forEach(function (kind, c) {
      const v = solved.status === 'ok' ? solved.drawn[R.linkage.columns_at + c] : NaN;
      out.push(kind === 'angle' ? coordinateOut('angle', v) : kind === 'length' ? v / R.length_per_unit : v);
    });
    out.push('');
    return out;
  }
  // The fixed guides of joints and links where these dimensions put them (from a drawn row).
  function guidesOf(solved) {
    const row = solved.find(function (x) { return x.drawn; });
    if (!row) return fileRows.guides;
    const L = R.linkage, v = row.drawn, guides = [];
    for (let g = 0; g < L.guide_count; ++g) {
      const k = L.guides_at + 4 * g;
      guides.push({ through: [v[k] / R.length_per_unit, v[k + 1] / R.length_per_unit], along: [v[k + 2], v[k + 3]] });
    }
    return guides;
  }
  // The drawing of a solved row: each segment a link vector of the drawing stage laid end to
  // end in kinema's order (engine/analysis/geometry.cpp MechanismGeometry::segments), each
  // point on a link drawn back along its vector; in the output length unit.
  function drawingOf(solved) {
    if (!solved.drawn) return null;
    const f = R.length_per_unit, v = solved.drawn;
    if (R.frame_count) {  // a chain: each frame's origin, then its x, y, z axes (motion_drawing.cpp chain_rows)
      const g = [];
      for (let fr = 0; fr < R.frame_count; ++fr) {
        // The tape's placement: origin, then the rotation row by row; + 0 as placed_frames: no signed zero.
        const k = R.frames_at + R.frame_outputs * fr;
        for (let c = 0; c < 3; ++c) g.push(v[k + c] / f + 0);
        for (let axis = 0; axis < 3; ++axis)
          for (let c = 0; c < 3; ++c) g.push(v[k + 3 + 3 * c + axis] + 0);
      }
      return g;
    }
    if (R.linkage) {  // joints and links: each drawn joint, then each block's angle
      const g = [];
      R.linkage.joints.forEach(function (k) { g.push(v[k] / f, v[k + 1] / f); });
      for (let b = 0; b < R.linkage.block_count; ++b) g.push(v[R.linkage.blocks_at + b]);
      return g;
    }
    const vector = function (t, part) { const k = R.vector_outputs * t + part; return [v[k], v[k + 1]]; };
    const g = [];
    let at = [0, 0];
    drawing.segments.forEach(function (s) {
      if (s.loop_start) at = [0, 0];
      const term = vector(s.term, R.vector_position_at);
      const from = at, to = [at[0] + term[0], at[1] + term[1]];
      at = to;
      let along = s.guide_from_tape ? vector(s.term, R.vector_guide_at) : term;
      const length = Math.hypot(along[0], along[1]);
      if (length > 0) along = [along[0] / length, along[1] / length];
      const block = s.block_at_from ? from : to;
      g.push(from[0] / f, from[1] / f, to[0] / f, to[1] / f, block[0] / f, block[1] / f, along[0], along[1]);
    });
    drawing.points_on_links.forEach(function (p) {
      if (solved.status !== 'ok') { g.push(NaN, NaN, NaN, NaN); return; }
      let k = 0;
      for (let j = 0; j < p.point; ++j) k += 3 * R.point_dimensions[j];
      const term = vector(p.vector, R.vector_position_at), x = solved.points[k], y = solved.points[k + 1];
      g.push((x - term[0]) / f, (y - term[1]) / f, x / f, y / f);
    });
    return g;
  }
  function reasonOf(solved) {
    if (solved.status === 'unassembled')
      return 'the loops do not close at ' + data.input.name + ' with these dimensions (Newton, continued from the value before, does not converge)';
    return solved.why === 'jacobian' ? 'the Jacobian of the loops is singular here with these dimensions (a toggle)'
      : 'the rates are not finite here with these dimensions';
  }
  // Solves every row for the sliders' values and puts the rows where the page reads them.
  function resolveRows() {
    const begun = performance.now();
    const values = R.parameters.map(function (p) { return p.value; });
    sliders.forEach(function (s) { values[s.index] = siValue(s.parameter, Number(s.input.value)); });
    solver.setParameters(values);
    const solved = solver.sweep(R.inputs);
    resolveTimes.push(performance.now() - begun);
    lastSolved = solved;
    resolved = sliders.some(function (s) { return Number(s.input.value) !== s.fileValue; });
    if (R.linkage) drawing.guides = resolved ? guidesOf(solved) : fileRows.guides;
    for (let r = 0; r < count; ++r) {
      if (!resolved) {
        rows[r] = fileRows.rows[r]; numbers[r] = fileRows.numbers[r]; drawing.rows[r] = fileRows.drawing[r];
        data.reasons[r] = fileRows.reasons[r];
        continue;
      }
      const fields = fieldsOf(solved[r]);
      numbers[r] = fields.map(function (v) { return typeof v === 'number' ? v : parseFloat(v); });
      rows[r] = fields.map(function (v) { return typeof v !== 'number' ? v : isFinite(v) ? String(Number(v.toPrecision(12))) : ''; });
      drawing.rows[r] = solved[r].status === 'unassembled' ? null : drawingOf(solved[r]);
      data.reasons[r] = solved[r].status === 'ok' ? '' : reasonOf(solved[r]);
    }
    sliders.forEach(function (s) { s.shown.textContent = s.input.value + ' ' + unitOf(s.parameter); });
    const failed = solved.filter(function (x) { return x.status !== 'ok'; }).length;
    sliderNote.textContent = !resolved ? 'The file\'s dimensions: the rows kinema solved.'
      : 'Solved here in ' + resolveTimes[resolveTimes.length - 1].toFixed(1) + ' ms' +
        (failed ? ': ' + failed + ' of ' + count + ' values not assembled or singular (marked on the scrubber).' : '.');
    drawMarks();
    measureReadout();
    buildPlots();
    drawTraces();
    setRow(row);
  }
  let sliderNote = null;
  if (solver) {
    node('h2', '', sliderArea, 'Dimensions');
    R.parameters.forEach(function (p, index) {
      if (!p.slider || !p.range) return;
      const shownValue = function (si) { return Number(outputValue(p, si).toPrecision(12)); };
      const fileValue = shownValue(p.value), low = shownValue(p.range.min), high = shownValue(p.range.max);
      // A move snaps to a round step (a power of ten, about a thousandth of the range) so that
      // the values read as written; the ends stay the analysis's, the file's value its own.
      const step = Math.pow(10, Math.floor(Math.log10(Math.max(high - low, 1e-9) / 1000)));
      const label = node('label', 'slider', sliderArea);
      node('span', 'name', label, p.name);
      const track = node('span', 'track', label);
      const input = node('input', '', track);
      input.type = 'range';
      input.step = 'any';
      input.min = low;
      input.max = high;
      input.value = fileValue;
      input.setAttribute('data-parameter', p.name);
      // The band: where the run goes through every value, no gap between (green); the rest of the track where only some assemble.
      const band = node('span', 'band', track);
      band.title = 'green: the mechanism runs through every value of the run; red: it assembles at some values only, or a gap lies between two';
      if (p.range.whole_min !== null && p.range.whole_max !== null) {
        const whole = node('span', 'whole', band);
        const at = function (si) { return (100 * (shownValue(si) - low) / (high - low || 1)).toFixed(3) + '%'; };
        whole.style.left = at(p.range.whole_min);
        whole.style.right = (100 - parseFloat(at(p.range.whole_max))).toFixed(3) + '%';
        whole.setAttribute('data-min', shownValue(p.range.whole_min));
        whole.setAttribute('data-max', shownValue(p.range.whole_max));
      }
      const shown = node('span', 'shown', label);
      const slider = { parameter: p, index: index, input: input, shown: shown, fileValue: fileValue };
      input.addEventListener('input', function () {
        const v = Number(input.value);
        if (v > low && v < high && v !== fileValue) input.value = Number((Math.round(v / step) * step).toPrecision(12));
        resolveRows();
      });
      sliders.push(slider);
    });
    const reset = node('button', '', sliderArea, 'The file\'s dimensions');
    reset.addEventListener('click', function () {
      sliders.forEach(function (s) { s.input.value = s.fileValue; });
      resolveRows();
    });
    sliderNote = node('p', 'key', sliderArea);
    sliders.forEach(function (s) { s.shown.textContent = s.input.value + ' ' + unitOf(s.parameter); });
    sliderNote.textContent = 'The file\'s dimensions: the rows kinema solved.';
  } else {
    sliderArea.style.display = 'none';
  }
  // Sets parameters (by name, in the file's output units) as the sliders would, and solves.
  function setDimensions(values) {
    sliders.forEach(function (s) { if (s.parameter.name in values) s.input.value = values[s.parameter.name]; });
    resolveRows();
  }

  // What a measurement reads (bench/page_timing.js): the times between frames while playing,
  // and the time each frame's drawing took.
  // The sliders' rows for a test: every row's status and fields (numbers in the CSV's units);
  // the readout of any row as it is shown (readoutOf).
  window.kinemaPage = { frameTimes: frameTimes, drawTimes: drawTimes, setPlaying: setPlaying, resolveTimes: resolveTimes,
    setDimensions: setDimensions, setRow: setRow, centres: rowCentres, polygons: rowPolygons, readout: readoutOf,
    rows: function () { return numbers.map(function (n, r) { return { status: status(r), fields: n.slice() }; }); } };
  // The derivation (static MathML written by kinema) under everything the script made.
  document.body.appendChild(document.getElementById('derivation'));
  fit();
  showKey();
  drawTraces();
  // Opened at the first value that assembles (the piston's run starts short of reach).
  const firstAssembled = rows.findIndex(function (unused, r) { return status(r) === 'ok'; });
  setRow(Math.max(firstAssembled, 0));
})();
