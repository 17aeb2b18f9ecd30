// ContactLab viewer (src/view/web/viewer.js): draws the data `contactlab view` embeds in the
// page (src/view/view_data.h) with three.js r111: the two bodies at their poses, the pointshell
// of the pointshell body coloured by level, a slice of the field body's signed distance field,
// and for an experiment's run the per-cycle poses and forces with a time slider and a force plot.
// Plain JS, no modules. When the first frame is drawn, <html data-ready="1"> is set.
(function () {
  'use strict';

  // --- Colours. Each family keeps clear of the others' hues so a screenshot can tell them
  // apart (tests/view/check_page.py): body A orange, body B blue, levels neither.
  var BODY_COLOURS = [0xe8862a, 0x2f6fd0];
  // Red is kept for points in contact.
  var LEVEL_COLOURS = ['#ffe14d', '#3cc83c', '#d040d0', '#40e0e0', '#a0ff60', '#9060ff',
                       '#f0f0f0', '#ff80c0', '#00a080', '#c0c000', '#b0b0ff', '#808080'];
  var CONTACT_COLOUR = '#ff1010';
  // Live contact marks: evaluated points sky blue (clear of body B's hue), the rest dim grey.
  var EVALUATED_COLOUR = '#38c8ff', UNEVALUATED_COLOUR = '#5a5e64';
  var FORCE_COLOUR = 0xff3030;

  // --- Options in the address's fragment: #job=I, #t=SECONDS, #model=NAME, #play (joined with &).
  var options = {};
  location.hash.replace(/^#/, '').split('&').forEach(function (kv) {
    if (!kv) return;
    var parts = kv.split('=');
    options[decodeURIComponent(parts[0])] = parts.length > 1 ? decodeURIComponent(parts[1]) : '';
  });

  // --- The data. A results folder of several jobs (view_data.h, SeveralJobsViewData) holds
  // every job's data, their long strings in shared "blobs": the page shows the job of #job=I
  // (the first when absent or not among them) and a selector that reloads it with another.
  var pageData = JSON.parse(document.getElementById('contactlab-data').textContent);
  var data = pageData, jobIndex = 0;
  function resolveBlobs(x, blobs) {
    if (Array.isArray(x)) return x.map(function (item) { return resolveBlobs(item, blobs); });
    if (x === null || typeof x !== 'object') return x;
    var keys = Object.keys(x);
    if (keys.length === 1 && keys[0] === '$blob') return blobs[x.$blob];
    var out = {};
    keys.forEach(function (k) { out[k] = resolveBlobs(x[k], blobs); });
    return out;
  }
  if (pageData.job_data) {
    pageData.jobs.forEach(function (j, i) { if (String(j.job) === options.job) jobIndex = i; });
    data = resolveBlobs(pageData.job_data[jobIndex], pageData.blobs);
    var jobSelect = document.getElementById('job');
    pageData.jobs.forEach(function (j) {
      jobSelect.appendChild(el('option', {value: String(j.job)}, 'job ' + j.job + (j.label ? ': ' + j.label : '')));
    });
    jobSelect.value = String(pageData.jobs[jobIndex].job);
    jobSelect.addEventListener('change', function () {
      location.hash = 'job=' + encodeURIComponent(jobSelect.value);
      location.reload();
    });
    document.getElementById('job-choice').hidden = false;
    document.documentElement.setAttribute('data-jobs', String(pageData.jobs.length));
  }
  if (data.replay) document.documentElement.setAttribute('data-job', String(data.replay.job));

  // Base64 text of little-endian bytes -> typed array of TYPE.
  function decode(text, Type) {
    var bin = atob(text);
    var bytes = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
    return new Type(bytes.buffer);
  }
  function setPose(object, p) {  // p: [x, y, z, qw, qx, qy, qz]
    object.position.set(p[0], p[1], p[2]);
    object.quaternion.set(p[4], p[5], p[6], p[3]).normalize();
  }
  function el(tag, attrs, text) {
    var e = document.createElement(tag);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function hex(c) { return '#' + ('000000' + c.toString(16)).slice(-6); }
  function fmt(v, digits) { return Number(v).toPrecision(digits || 3); }

  // --- Renderer, camera, lights. World frame is z-up, as in the scenes.
  var container = document.getElementById('view');
  var renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(0x1d2024);
  container.appendChild(renderer.domElement);
  var scene = new THREE.Scene();
  var camera = new THREE.PerspectiveCamera(40, window.innerWidth / window.innerHeight, 1e-4, 100);
  camera.up.set(0, 0, 1);
  scene.add(camera);
  scene.add(new THREE.AmbientLight(0xffffff, 0.5));
  var light = new THREE.DirectionalLight(0xffffff, 0.7);
  light.position.set(0.3, 0.5, 1);
  camera.add(light);

  // --- The bodies: a group per body at its pose holding its mesh (and A's points, B's slice).
  var bodies = data.bodies.map(function (b, i) {
    var group = new THREE.Group();
    group.name = b.name;
    setPose(group, b.pose);
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(decode(b.positions, Float32Array), 3));
    geometry.setIndex(new THREE.BufferAttribute(decode(b.indices, Uint32Array), 1));
    geometry.computeVertexNormals();
    var material = new THREE.MeshLambertMaterial({color: BODY_COLOURS[i], side: THREE.DoubleSide,
                                                  transparent: true, opacity: 0.55, depthWrite: false});
    var mesh = new THREE.Mesh(geometry, material);
    mesh.renderOrder = 2;
    group.add(mesh);
    scene.add(group);
    var body = {spec: b, group: group, mesh: mesh};
    // A deformable body of a replay: rest positions and the reduced basis (#V x 3 x r) at its
    // vertices, so that a frame's coordinates q deform it (u = U q).
    if (b.basis) {
      body.rest = geometry.attributes.position.array.slice();
      body.basis = decode(b.basis, Float32Array);
      body.modes = b.modes;
    }
    return body;
  });
  // Deforms BODY's mesh by reduced coordinates Q (from OFFSET, body.modes entries).
  function deform(body, q, offset) {
    var pos = body.mesh.geometry.attributes.position, a = pos.array, U = body.basis, r = body.modes;
    for (var n = 0; n < a.length; ++n) {
      var u = 0;
      for (var m = 0; m < r; ++m) u += U[n * r + m] * q[offset + m];
      a[n] = body.rest[n] + u;
    }
    pos.needsUpdate = true;
    body.mesh.geometry.computeVertexNormals();
    body.mesh.geometry.computeBoundingSphere();
  }

  // --- The pointshell of body A, coloured by the level that adds each point.
  var points = null, contactPoints = null;
  if (data.pointshell) {
    var ps = data.pointshell;
    var positions = decode(ps.positions, Float32Array);
    var levels = decode(ps.level, Uint8Array);
    var colours = new Float32Array(levels.length * 3);
    var c = new THREE.Color();
    for (var i = 0; i < levels.length; ++i) {
      c.set(LEVEL_COLOURS[levels[i] % LEVEL_COLOURS.length]);
      colours[3 * i] = c.r; colours[3 * i + 1] = c.g; colours[3 * i + 2] = c.b;
    }
    var pg = new THREE.BufferGeometry();
    pg.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    pg.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    points = new THREE.Points(pg, new THREE.PointsMaterial({size: 2.5, sizeAttenuation: false,
                                                            vertexColors: THREE.VertexColors}));
    points.renderOrder = 1;
    bodies[ps.body].group.add(points);
    // The points in contact at the start poses, larger and red (a scene page only: in a replay
    // or live view the bodies move on).
    if (ps.contact && !data.replay && !data.live) {
      var flags = decode(ps.contact, Uint8Array), touching = [];
      for (var m = 0; m < flags.length; ++m) {
        if (flags[m]) touching.push(positions[3 * m], positions[3 * m + 1], positions[3 * m + 2]);
      }
      if (touching.length > 0) {
        var cg = new THREE.BufferGeometry();
        cg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(touching), 3));
        // Drawn through everything: the contact region is usually hidden inside the other body.
        // Transparent, so that it is drawn with (after, by renderOrder) the translucent bodies.
        contactPoints = new THREE.Points(cg, new THREE.PointsMaterial({size: 4, sizeAttenuation: false, color: CONTACT_COLOUR,
                                                                       depthTest: false, transparent: true, depthWrite: false}));
        contactPoints.renderOrder = 5;
        bodies[ps.body].group.add(contactPoints);
      }
    }
  }

  // --- A slice of body B's distance field: green inside (d < 0), purple outside, paler near
  // the surface, black on the zero contour, darker isolines every 4 grid cells.
  var slice = null;
  function sliceColour(d, scale, out, o) {
    var t = Math.min(1, Math.abs(d) / scale);
    if (d < 0) { out[o] = 40 + 60 * (1 - t); out[o + 1] = 110 + 120 * (1 - t); out[o + 2] = 70 + 90 * (1 - t); }
    else { out[o] = 110 + 110 * (1 - t); out[o + 1] = 50 + 60 * (1 - t); out[o + 2] = 130 + 110 * (1 - t); }
    out[o + 3] = 255;
  }
  if (data.slice) {
    var s = data.slice;
    var values = decode(s.values, Float32Array);
    var w = s.width, h = s.height;
    var rgba = new Uint8Array(w * h * 4);
    var scale = Math.max(Math.abs(s.min), Math.abs(s.max), 1e-12);
    var iso = 4 * s.spacing;
    for (var j = 0; j < h; ++j) {
      for (var k = 0; k < w; ++k) {
        var n = j * w + k, v0 = values[n];
        sliceColour(v0, scale, rgba, 4 * n);
        // A contour passes between this sample and its right or upper neighbour: the zero
        // contour (sign change) in black, an isoline (another multiple of ISO) darkened.
        var band = Math.floor(v0 / iso), zero = false, line = false;
        var neighbours = [k + 1 < w ? values[n + 1] : v0, j + 1 < h ? values[n + w] : v0];
        for (var m = 0; m < 2; ++m) {
          if ((v0 < 0) !== (neighbours[m] < 0)) zero = true;
          else if (Math.floor(neighbours[m] / iso) !== band) line = true;
        }
        if (zero) { rgba[4 * n] = rgba[4 * n + 1] = rgba[4 * n + 2] = 0; }
        else if (line) { rgba[4 * n] *= 0.7; rgba[4 * n + 1] *= 0.7; rgba[4 * n + 2] *= 0.7; }
      }
    }
    var texture = new THREE.DataTexture(rgba, w, h, THREE.RGBAFormat);
    texture.magFilter = THREE.NearestFilter;
    texture.minFilter = THREE.LinearFilter;
    texture.generateMipmaps = false;
    texture.needsUpdate = true;
    // A quad from the centre of sample (0, 0) to the centre of sample (w-1, h-1).
    var P = function (a, b) {
      return [s.corner[0] + a * s.u[0] + b * s.v[0], s.corner[1] + a * s.u[1] + b * s.v[1],
              s.corner[2] + a * s.u[2] + b * s.v[2]];
    };
    var quad = [].concat(P(0, 0), P(w - 1, 0), P(w - 1, h - 1), P(0, h - 1));
    var du = 0.5 / w, dv = 0.5 / h;
    var sg = new THREE.BufferGeometry();
    sg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(quad), 3));
    sg.setAttribute('uv', new THREE.BufferAttribute(new Float32Array([du, dv, 1 - du, dv, 1 - du, 1 - dv, du, 1 - dv]), 2));
    sg.setIndex([0, 1, 2, 0, 2, 3]);
    slice = new THREE.Mesh(sg, new THREE.MeshBasicMaterial({map: texture, side: THREE.DoubleSide}));
    slice.renderOrder = 0;
    bodies[s.body].group.add(slice);
  }

  // --- Contact surfaces (pressure-field): triangles in the world, coloured by pressure from
  // dark teal (0) through green to pale yellow (the largest), hues clear of the bodies' and the
  // contact red, drawn over the bodies.
  var PRESSURE_STOPS = [[0, 80, 70], [120, 200, 60], [255, 240, 120]];
  function pressureColour(t, out, o) {
    t = Math.max(0, Math.min(1, t));
    var a = t < 0.5 ? PRESSURE_STOPS[0] : PRESSURE_STOPS[1], b = t < 0.5 ? PRESSURE_STOPS[1] : PRESSURE_STOPS[2];
    var u = t < 0.5 ? 2 * t : 2 * t - 1;
    for (var k = 0; k < 3; ++k) out[o + k] = (a[k] + u * (b[k] - a[k])) / 255;
  }
  function surfaceMesh() {
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(0), 3));
    g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(0), 3));
    var m = new THREE.Mesh(g, new THREE.MeshBasicMaterial({vertexColors: THREE.VertexColors, side: THREE.DoubleSide,
                                                           depthTest: false, transparent: true, opacity: 0.9}));
    m.renderOrder = 4;
    scene.add(m);
    return m;
  }
  // Shows triangles FIRST..END of CORNERS (9 floats each) and PRESSURE (3 each) on MESH.
  function setSurface(mesh, corners, pressure, pmax, first, end) {
    var pos = corners.slice(9 * first, 9 * end), col = new Float32Array(pos.length);
    for (var i = 0; i < pos.length / 3; ++i) pressureColour(pressure[3 * first + i] / Math.max(pmax, 1e-30), col, 3 * i);
    mesh.geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    mesh.geometry.setAttribute('color', new THREE.BufferAttribute(col, 3));
    mesh.geometry.computeBoundingSphere();
  }
  var surfaces = (data.surfaces || []).map(function (sf) {
    var mesh = surfaceMesh(), corners = decode(sf.corners, Float32Array);
    setSurface(mesh, corners, decode(sf.pressure, Float32Array), sf.pmax, 0, corners.length / 9);
    return {spec: sf, mesh: mesh};
  });
  var replaySurface = null;  // the current track's surface in a replay

  // --- Replay: per-cycle poses and wrenches of each model.
  var replay = data.replay || null;
  var tracks = [];
  var arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 0.01, FORCE_COLOUR);
  arrow.visible = false;
  // Drawn over everything: it starts at the moving body's origin, often inside a body.
  arrow.renderOrder = 3;
  arrow.line.material.depthTest = false;
  arrow.cone.material.depthTest = false;
  scene.add(arrow);

  // --- Camera framing: the bounding sphere of both bodies at their start poses.
  function frame() {
    scene.updateMatrixWorld(true);  // the bodies' poses, before the first render computes them
    var box = new THREE.Box3();
    bodies.forEach(function (b) { box.expandByObject(b.mesh); });
    var sphere = box.getBoundingSphere(new THREE.Sphere());
    var r = Math.max(sphere.radius, 1e-3);
    var dir = new THREE.Vector3(1.0, -1.6, 0.9).normalize();
    camera.position.copy(sphere.center).addScaledVector(dir, 2.7 * r);
    camera.near = r * 0.01;
    camera.far = r * 50;
    camera.updateProjectionMatrix();
    return sphere;
  }
  var bounds = frame();
  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(bounds.center);
  controls.update();

  // --- Panel: title, legend, toggles.
  document.getElementById('title').textContent = data.title || 'ContactLab';
  document.getElementById('subtitle').textContent =
      replay ? (replay.folder + ', job ' + replay.job + (replay.label ? ' (' + replay.label + ')' : '')) : (data.scene || '');
  var legend = document.getElementById('legend');
  bodies.forEach(function (b, i) {
    var row = el('div', {'class': 'row'});
    row.appendChild(el('span', {'class': 'swatch', style: 'background:' + hex(BODY_COLOURS[i])}));
    var how = !b.spec.deformable ? '' : b.basis ? ', deformable: mesh deformed per frame, points at rest'
                                               : ', deformable, shown at rest';
    var triangles = b.spec.source_triangles > b.spec.triangles
        ? b.spec.source_triangles + ' \u2192 ' + b.spec.triangles + ' triangles for display' : b.spec.triangles + ' triangles';
    row.appendChild(el('span', {}, b.spec.name + ' (' + b.spec.role + how + ', ' + triangles + ')'));
    legend.appendChild(row);
  });
  if (data.pointshell) {
    var ps2 = data.pointshell;
    var shown = ps2.kept.reduce(function (a, b) { return a + b; }, 0);
    legend.appendChild(el('div', {'class': 'small'}, 'pointshell: ' + ps2.points + ' points, ' + ps2.levels +
                                                    ' levels; ' + shown + ' drawn'));
    ps2.kept.forEach(function (kept, l) {
      var row = el('div', {'class': 'row small level-row'});
      row.appendChild(el('span', {'class': 'swatch', style: 'background:' + LEVEL_COLOURS[l % LEVEL_COLOURS.length]}));
      row.appendChild(el('span', {}, 'level ' + l + ': ' + kept + (kept < ps2.total[l] ? ' of ' + ps2.total[l] : '') + ' points'));
      legend.appendChild(row);
    });
    if (contactPoints) {
      var crow = el('div', {'class': 'row small'});
      crow.appendChild(el('span', {'class': 'swatch', style: 'background:' + CONTACT_COLOUR}));
      crow.appendChild(el('span', {}, 'in contact at the start (d < 0): ' + ps2.in_contact + ' of ' + ps2.points + ' points'));
      legend.appendChild(crow);
    }
  }
  if (data.slice) {
    var s2 = data.slice;
    legend.appendChild(el('div', {'class': 'small'}, 'field of ' + bodies[s2.body].spec.name + ', slice ' +
                                                    'xyz'[s2.axis] + ' = ' + fmt(s2.at) + ' m (body frame)'));
    legend.appendChild(el('div', {'class': 'colorbar', style:
        'background: linear-gradient(to right, rgb(40,110,70), rgb(100,230,160) 49%, #000 49.5%, #000 50.5%, ' +
        'rgb(220,110,240) 51%, rgb(110,50,130))'}));
    legend.appendChild(el('div', {'class': 'small'}, 'd from ' + fmt(s2.min) + ' m (inside, green) to ' + fmt(s2.max) +
                                                    ' m (outside, purple); black: d = 0; isolines every ' +
                                                    fmt(4 * s2.spacing) + ' m'));
  }
  function surfaceLegend(text) {
    legend.appendChild(el('div', {'class': 'colorbar', style:
        'background: linear-gradient(to right, ' + PRESSURE_STOPS.map(function (c) { return 'rgb(' + c.join(',') + ')'; }).join(', ') + ')'}));
    legend.appendChild(el('div', {'class': 'small surface-legend'}, text));
  }
  surfaces.forEach(function (sf) {
    surfaceLegend('contact surface of ' + sf.spec.model + ': ' + sf.spec.triangles + ' triangles' +
                  (sf.spec.triangles >= sf.spec.max_triangles ? ' (the first ' + sf.spec.max_triangles + ')' : '') +
                  ', pressure 0 to ' + fmt(sf.spec.pmax) + ' Pa');
  });
  if (replay && replay.models.some(function (m) { return m.surface; })) {
    surfaceLegend('contact surface (pressure-field models), at ' + replay.models.filter(function (m) { return m.surface; })
                  .map(function (m) { return m.name + ': ' + decode(m.surface.frames, Int32Array).length; }).join(', ') +
                  ' frames, each at the kept frame at or before the one shown; pressure 0 to the model\'s largest');
  }
  var toggles = document.getElementById('toggles');
  function toggle(label, objects, on) {
    var box = el('input', {type: 'checkbox'});
    box.checked = on;
    objects.forEach(function (o) { o.visible = on; });
    box.addEventListener('change', function () { objects.forEach(function (o) { o.visible = box.checked; }); });
    var lab = el('label');
    lab.appendChild(box);
    lab.appendChild(document.createTextNode(' ' + label));
    toggles.appendChild(lab);
  }
  bodies.forEach(function (b) { toggle(b.spec.name, [b.mesh], true); });
  if (points) toggle('points', [points], true);
  if (contactPoints) toggle('contact', [contactPoints], true);
  if (slice) toggle('slice', [slice], true);
  surfaces.forEach(function (sf) { toggle(sf.spec.model + ' surface', [sf.mesh], true); });
  var solid = el('input', {type: 'checkbox'});
  solid.addEventListener('change', function () {
    bodies.forEach(function (b) {
      b.mesh.material.transparent = !solid.checked;
      b.mesh.material.depthWrite = solid.checked;
      b.mesh.material.opacity = solid.checked ? 1 : 0.55;
      b.mesh.material.needsUpdate = true;
    });
  });
  var solidLabel = el('label');
  solidLabel.appendChild(solid);
  solidLabel.appendChild(document.createTextNode(' solid'));
  toggles.appendChild(solidLabel);

  // --- Replay controls and the force plot.
  var current = 0;       // track index
  var frameIndex = 0;    // frame of the current track
  var playing = false, playTime = 0, lastWall = null;
  var plot = document.getElementById('plot');
  function magnitude(f, i) { return Math.hypot(f[3 * i], f[3 * i + 1], f[3 * i + 2]); }
  if (replay) {
    document.getElementById('replay').hidden = false;
    tracks = replay.models.map(function (m) {
      var t = decode(m.t, Float32Array), force = decode(m.force, Float32Array);
      var fmag = new Float32Array(t.length), fmax = 0;
      for (var i = 0; i < t.length; ++i) { fmag[i] = magnitude(force, i); fmax = Math.max(fmax, fmag[i]); }
      return {name: m.name, cycles: m.cycles, t: t, pose: decode(m.pose, Float32Array), force: force,
              torque: decode(m.torque, Float32Array), level: decode(m.level, Int32Array),
              contacts: decode(m.contacts, Int32Array), fmag: fmag, fmax: fmax,
              r: m.r || 0, q: m.r ? decode(m.q, Float32Array) : null,
              r_B: m.r_B || 0, q_B: m.r_B ? decode(m.q_B, Float32Array) : null,
              surface: m.surface ? {frames: decode(m.surface.frames, Int32Array), start: decode(m.surface.start, Uint32Array),
                                    corners: decode(m.surface.corners, Float32Array),
                                    pressure: decode(m.surface.pressure, Float32Array), pmax: m.surface.pmax} : null};
    });
    if (tracks.some(function (tr) { return tr.surface; })) {
      replaySurface = surfaceMesh();
      toggle('contact surface', [replaySurface], true);
    }
    var select = document.getElementById('model');
    tracks.forEach(function (tr, i) { select.appendChild(el('option', {value: String(i)}, tr.name)); });
    if (tracks.length < 2) document.getElementById('model-choice').hidden = true;
    select.addEventListener('change', function () {
      var t = tracks[current].t[frameIndex];
      current = Number(select.value);
      showTime(t);
    });
    var slider = document.getElementById('slider');
    slider.addEventListener('input', function () { playing = false; updatePlayButton(); showFrame(Number(slider.value)); });
    var play = document.getElementById('play');
    play.addEventListener('click', function () {
      var tr = tracks[current];
      if (!playing && frameIndex >= tr.t.length - 1) showFrame(0);
      playing = !playing;
      playTime = tr.t[frameIndex];
      lastWall = null;
      updatePlayButton();
    });
    plot.addEventListener('click', function (e) {
      var r = plot.getBoundingClientRect(), tr = tracks[current];
      var x = (e.clientX - r.left - plotArea.left) / plotArea.width;
      showTime(tr.t[0] + Math.max(0, Math.min(1, x)) * (tr.t[tr.t.length - 1] - tr.t[0]));
    });
  }
  function updatePlayButton() { document.getElementById('play').textContent = playing ? 'Pause' : 'Play'; }

  // The frame of the current track at or just before time T.
  function showTime(t) {
    var tt = tracks[current].t, lo = 0, hi = tt.length - 1;
    while (lo < hi) { var mid = (lo + hi + 1) >> 1; if (tt[mid] <= t) lo = mid; else hi = mid - 1; }
    showFrame(lo);
  }
  function showFrame(i) {
    var tr = tracks[current];
    frameIndex = Math.max(0, Math.min(tr.t.length - 1, i));
    var slider = document.getElementById('slider');
    slider.max = String(tr.t.length - 1);
    slider.value = String(frameIndex);
    var p = tr.pose.subarray(7 * frameIndex, 7 * frameIndex + 7);
    var moving = bodies[replay.moving];
    setPose(moving.group, p);
    if (bodies[0].basis && tr.q && tr.r === bodies[0].modes) deform(bodies[0], tr.q, tr.r * frameIndex);
    if (bodies[1].basis && tr.q_B && tr.r_B === bodies[1].modes) deform(bodies[1], tr.q_B, tr.r_B * frameIndex);
    // The force on the moving body at its origin, scaled so the largest force of the run is
    // 60% of the scene's radius.
    var f = new THREE.Vector3(tr.force[3 * frameIndex], tr.force[3 * frameIndex + 1], tr.force[3 * frameIndex + 2]);
    var fm = f.length();
    arrow.visible = fm > 1e-9 * Math.max(tr.fmax, 1e-12) && fm > 0;
    if (arrow.visible) {
      var len = 0.6 * bounds.radius * fm / Math.max(tr.fmax, 1e-12);
      arrow.position.set(p[0], p[1], p[2]);
      arrow.setDirection(f.multiplyScalar(1 / fm));
      arrow.setLength(Math.max(len, 1e-6), 0.25 * len, 0.12 * len);
    }
    if (replaySurface) showSurface(tr);
    var torque = Math.hypot(tr.torque[3 * frameIndex], tr.torque[3 * frameIndex + 1], tr.torque[3 * frameIndex + 2]);
    document.getElementById('readout').textContent =
        't = ' + tr.t[frameIndex].toFixed(3) + ' s   |F| = ' + fmt(fm) + ' N   |T| = ' + fmt(torque) + ' N m' +
        (tr.level[frameIndex] >= 0 ? '   level ' + tr.level[frameIndex] : '') + '   contacts ' + tr.contacts[frameIndex];
    drawPlot();
  }

  // The contact surface of TR at the last kept frame at or before the one shown (none for a
  // model without one).
  function showSurface(tr) {
    var sf = tr.surface;
    replaySurface.userData.model = sf ? tr.name : '';
    if (!sf) { setSurface(replaySurface, new Float32Array(0), new Float32Array(0), 1, 0, 0); return; }
    var lo = 0, hi = sf.frames.length - 1;
    while (lo < hi) { var mid = (lo + hi + 1) >> 1; if (sf.frames[mid] <= frameIndex) lo = mid; else hi = mid - 1; }
    setSurface(replaySurface, sf.corners, sf.pressure, sf.pmax, sf.start[lo], sf.start[lo + 1]);
    replaySurface.userData.frame = sf.frames[lo];
  }

  // |F| against t of every model (the current one bright), with a cursor at the current frame.
  var plotArea = {left: 56, top: 8, width: 1, height: 1};
  function drawPlot() {
    var dpr = window.devicePixelRatio || 1;
    var cw = plot.clientWidth, ch = plot.clientHeight;
    if (plot.width !== Math.round(cw * dpr)) { plot.width = Math.round(cw * dpr); plot.height = Math.round(ch * dpr); }
    var g = plot.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, cw, ch);
    plotArea.width = Math.max(10, cw - plotArea.left - 10);
    plotArea.height = Math.max(10, ch - plotArea.top - 24);
    var tr = tracks[current];
    var t0 = tr.t[0], t1 = tr.t[tr.t.length - 1];
    if (!(t1 > t0)) t1 = t0 + 1;
    var fmax = 0;
    tracks.forEach(function (x) { fmax = Math.max(fmax, x.fmax); });
    if (!(fmax > 0)) fmax = 1;
    var X = function (t) { return plotArea.left + (t - t0) / (t1 - t0) * plotArea.width; };
    var Y = function (f) { return plotArea.top + plotArea.height * (1 - f / fmax); };
    // Axes and labels.
    g.strokeStyle = '#70757c';
    g.lineWidth = 1;
    g.strokeRect(plotArea.left, plotArea.top, plotArea.width, plotArea.height);
    g.fillStyle = '#c8ccd2';
    g.font = '11px sans-serif';
    g.textAlign = 'right';
    g.fillText(fmt(fmax) + ' N', plotArea.left - 4, plotArea.top + 9);
    g.fillText('0', plotArea.left - 4, plotArea.top + plotArea.height);
    g.save();
    g.translate(12, plotArea.top + plotArea.height / 2);
    g.rotate(-Math.PI / 2);
    g.textAlign = 'center';
    g.fillText('|F| (N)', 0, 0);
    g.restore();
    g.textAlign = 'center';
    g.textAlign = 'left';
    g.fillText(t0.toFixed(2), plotArea.left, ch - 6);
    g.textAlign = 'right';
    g.fillText(t1.toFixed(2), plotArea.left + plotArea.width, ch - 6);
    g.textAlign = 'center';
    g.fillText('t (s)', plotArea.left + plotArea.width / 2, ch - 6);
    // Curves: the others grey, the current one yellow.
    tracks.forEach(function (x, k) {
      if (k === current) return;
      curve(g, x, X, Y, '#6c7178');
    });
    curve(g, tr, X, Y, '#ffd000');
    // Cursor.
    g.strokeStyle = '#ffffff';
    g.beginPath();
    g.moveTo(X(tr.t[frameIndex]) + 0.5, plotArea.top);
    g.lineTo(X(tr.t[frameIndex]) + 0.5, plotArea.top + plotArea.height);
    g.stroke();
  }
  function curve(g, x, X, Y, colour) {
    g.strokeStyle = colour;
    g.lineWidth = 1.25;
    g.beginPath();
    // At most ~2 samples per pixel.
    var step = Math.max(1, Math.floor(x.t.length / (2 * plotArea.width)));
    for (var i = 0; i < x.t.length; i += step) {
      if (i === 0) g.moveTo(X(x.t[i]), Y(x.fmag[i])); else g.lineTo(X(x.t[i]), Y(x.fmag[i]));
    }
    g.stroke();
  }

  if (replay && tracks.length > 0) {
    if (options.model !== undefined) {
      tracks.forEach(function (tr, i) { if (tr.name === options.model) current = i; });
      document.getElementById('model').value = String(current);
    }
    if (options.t !== undefined) showTime(Number(options.t)); else showFrame(0);
    if (options.play !== undefined) { playing = true; playTime = tracks[current].t[frameIndex]; updatePlayButton(); }
  }

  // --- Live session: snapshots from the server's event stream move the haptic body; the
  // device (manipulandum) pose is a grey wireframe ghost; the plot shows the last 10 s.
  var live = data.live || null;
  if (live) {
    document.getElementById('replay').hidden = false;
    ['play', 'slider', 'model-choice'].forEach(function (id) { document.getElementById(id).hidden = true; });
    document.getElementById('speed').parentNode.hidden = true;
    document.getElementById('subtitle').textContent = 'live: model ' + live.model + ', device ' + live.device;
    var haptic = bodies[live.haptic];
    var ghost = new THREE.Mesh(haptic.mesh.geometry, new THREE.MeshBasicMaterial(
        {color: 0xbbbbbb, wireframe: true, transparent: true, opacity: 0.3, depthWrite: false}));
    ghost.renderOrder = 4;
    setPose(ghost, haptic.spec.pose);
    scene.add(ghost);
    // A model's proxy of the haptic body (pointshell-ccd: where it is held outside the other
    // body) as a cyan wireframe, shown while the snapshots carry one.
    var proxy = new THREE.Mesh(haptic.mesh.geometry, new THREE.MeshBasicMaterial(
        {color: 0x17becf, wireframe: true, transparent: true, opacity: 0.5, depthWrite: false}));
    proxy.renderOrder = 5;
    proxy.visible = false;
    scene.add(proxy);
    var history = [];  // [t, |F|] of the last 10 s
    var liveMax = 0;
    var received = 0;
    var stream = new EventSource(live.stream);
    stream.onmessage = function (e) {
      var s = JSON.parse(e.data);
      ++received;
      setPose(haptic.group, s.body);
      setPose(ghost, s.device);
      proxy.visible = !!s.proxy;
      if (s.proxy) setPose(proxy, s.proxy);
      var f = new THREE.Vector3(s.force[0], s.force[1], s.force[2]);
      var fm = f.length();
      liveMax = Math.max(liveMax, fm);
      arrow.visible = fm > 0;
      if (arrow.visible) {
        var len = 0.6 * bounds.radius * fm / liveMax;
        arrow.position.set(s.body[0], s.body[1], s.body[2]);
        arrow.setDirection(f.multiplyScalar(1 / fm));
        arrow.setLength(Math.max(len, 1e-6), 0.25 * len, 0.12 * len);
      }
      document.getElementById('readout').textContent =
          't = ' + s.t.toFixed(3) + ' s   |F| = ' + fmt(fm) + ' N   |T| = ' +
          fmt(Math.hypot(s.torque[0], s.torque[1], s.torque[2])) + ' N m' +
          (s.level >= 0 ? '   level ' + s.level : '') + '   contacts ' + s.contacts + '   cycle ' +
          s.work_us.toFixed(0) + ' us';
      document.documentElement.setAttribute('data-snapshots', String(received));
      history.push([s.t, fm]);
      while (history.length > 1 && history[0][0] < s.t - 10) history.shift();
      var t = new Float32Array(history.length), fmag = new Float32Array(history.length), fmax = 0;
      for (var i = 0; i < history.length; ++i) { t[i] = history[i][0]; fmag[i] = history[i][1]; fmax = Math.max(fmax, fmag[i]); }
      tracks = [{name: live.model, t: t, fmag: fmag, fmax: fmax}];
      current = 0;
      frameIndex = history.length - 1;
      drawPlot();
    };
    // Per-point contact state of the drawn points, from a sweep over a few consecutive cycles
    // (docs/viewer.md): red in contact (d < 0), blue evaluated (d >= 0), grey not evaluated.
    if (points) {
      var markColours = [UNEVALUATED_COLOUR, EVALUATED_COLOUR, CONTACT_COLOUR].map(function (h) { return new THREE.Color(h); });
      var marksRow = null, marksReceived = 0;
      // The points in contact again, larger and through everything, as on a scene page: they
      // usually lie inside the other body.
      var drawnPositions = points.geometry.attributes.position.array;
      var touchingGeometry = new THREE.BufferGeometry();
      touchingGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(drawnPositions.length), 3));
      touchingGeometry.setDrawRange(0, 0);
      // Transparent, so that it is drawn with (after, by renderOrder) the translucent bodies.
      var touching = new THREE.Points(touchingGeometry, new THREE.PointsMaterial(
          {size: 5, sizeAttenuation: false, color: CONTACT_COLOUR, depthTest: false, transparent: true, depthWrite: false}));
      touching.renderOrder = 5;
      touching.frustumCulled = false;
      points.add(touching);  // same frame; hidden with the points
      stream.addEventListener('marks', function (e) {
        var m = JSON.parse(e.data);
        var packed = decode(m.states, Uint8Array);
        var col = points.geometry.attributes.color, a = col.array;
        var n = Math.min(m.points, a.length / 3), counts = [0, 0, 0];
        var tp = touchingGeometry.attributes.position;
        for (var i = 0; i < n; ++i) {
          var state = (packed[i >> 2] >> (2 * (i & 3))) & 3, mc = markColours[state] || markColours[0];
          if (state === 2) {
            tp.array[3 * counts[2]] = drawnPositions[3 * i];
            tp.array[3 * counts[2] + 1] = drawnPositions[3 * i + 1];
            tp.array[3 * counts[2] + 2] = drawnPositions[3 * i + 2];
          }
          ++counts[state];
          a[3 * i] = mc.r; a[3 * i + 1] = mc.g; a[3 * i + 2] = mc.b;
        }
        col.needsUpdate = true;
        tp.needsUpdate = true;
        touchingGeometry.setDrawRange(0, counts[2]);
        if (!marksRow) {  // the points now show contact state, not level
          Array.prototype.forEach.call(document.querySelectorAll('.level-row'), function (r) { r.hidden = true; });
          marksRow = el('div', {'class': 'small'});
          legend.appendChild(marksRow);
        }
        marksRow.innerHTML = '';
        [[CONTACT_COLOUR, 'in contact (d < 0): ' + counts[2]], [EVALUATED_COLOUR, 'evaluated, d >= 0: ' + counts[1]],
         [UNEVALUATED_COLOUR, 'not evaluated: ' + counts[0]]].forEach(function (x) {
          var r = el('div', {'class': 'row small'});
          r.appendChild(el('span', {'class': 'swatch', style: 'background:' + x[0]}));
          r.appendChild(el('span', {}, x[1]));
          marksRow.appendChild(r);
        });
        marksRow.appendChild(el('div', {'class': 'small'}, 'drawn points by contact state, cycles ' + m.first_cycle +
                                                         '-' + m.last_cycle));
        document.documentElement.setAttribute('data-marks', String(++marksReceived));
        document.documentElement.setAttribute('data-marks-contact', String(counts[2]));
        // Where the panel is (x,y,w,h, CSS px): its legend swatches are not points.
        var pr = document.getElementById('panel').getBoundingClientRect();
        document.documentElement.setAttribute('data-panel', [pr.left, pr.top, pr.width, pr.height].map(Math.round).join(','));
      });
    }
    stream.onerror = function () {
      // The session ended (or the server went away): keep the last pose.
      stream.close();
      document.getElementById('readout').textContent += '   (stream ended)';
    };
  }

  // --- Animation loop.
  // The 3D view fills the window above the replay / live bar.
  function layout() {
    var bar = document.getElementById('replay');
    container.style.bottom = bar.hidden ? '0px' : bar.offsetHeight + 'px';
    var w = Math.max(1, container.clientWidth), h = Math.max(1, container.clientHeight);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    renderer.setSize(w, h);
    if (tracks.length > 0) drawPlot();
  }
  layout();
  window.addEventListener('resize', layout);
  // #bench=orbit[&frames=N]: after the first frame the camera circles the scene once in N
  // frames (default 240); the mean and 95th-percentile time between frames (requestAnimationFrame
  // timestamps), in ms, go to data-bench-mean-ms and data-bench-p95-ms on <html> and to
  // window.contactlabBench.
  var bench = options.bench === 'orbit' ? {n: Math.max(2, Number(options.frames) || 240), times: [], last: null} : null;
  function benchFrame(now) {
    if (bench.last !== null) bench.times.push(now - bench.last);
    bench.last = now;
    var offset = camera.position.clone().sub(controls.target);
    offset.applyAxisAngle(camera.up, 2 * Math.PI / bench.n);
    camera.position.copy(controls.target).add(offset);
    camera.lookAt(controls.target);
    if (bench.times.length === bench.n) {
      var sorted = bench.times.slice().sort(function (a, b) { return a - b; });
      var mean = sorted.reduce(function (a, b) { return a + b; }, 0) / sorted.length;
      var p95 = sorted[Math.min(sorted.length - 1, Math.floor(0.95 * sorted.length))];
      window.contactlabBench = {frames: sorted.length, mean_ms: mean, p95_ms: p95};
      document.documentElement.setAttribute('data-bench-mean-ms', mean.toFixed(2));
      document.documentElement.setAttribute('data-bench-p95-ms', p95.toFixed(2));
      bench = null;
    }
  }
  var frames = 0;
  function animate(now) {
    requestAnimationFrame(animate);
    if (bench && frames > 0) benchFrame(now);
    if (playing && tracks.length > 0) {
      var tr = tracks[current];
      if (lastWall !== null) playTime += (now - lastWall) / 1000 * Number(document.getElementById('speed').value);
      lastWall = now;
      if (playTime >= tr.t[tr.t.length - 1]) { playTime = tr.t[tr.t.length - 1]; playing = false; updatePlayButton(); }
      showTime(playTime);
    }
    controls.update();
    renderer.render(scene, camera);
    if (++frames === 1) {
      document.documentElement.setAttribute('data-ready', '1');
      // Time from the start of navigation to the first frame drawn, ms.
      document.documentElement.setAttribute('data-ready-ms', performance.now().toFixed(0));
      window.contactlabReady = true;
    }
  }
  requestAnimationFrame(animate);
})();
