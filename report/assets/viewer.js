// The 3D view of a dresskit report page: reads the meshes embedded in the page (#dresskit-data),
// draws them with three.js (THREE, inlined before this script), orbits with OrbitControls, and
// offers toggles per mesh, the shape shown (placed, dressed, ...), and the colouring: plain, parts,
// or one of the per-vertex colour maps. It draws on demand (after a change), not in a loop.
(function () {
  'use strict';
  var start = performance.now();
  var view = document.getElementById('view');
  var dataNode = document.getElementById('dresskit-data');
  if (!view || !dataNode) return;
  var data = JSON.parse(dataNode.textContent);
  if (!data.meshes || data.meshes.length === 0) return;

  function noView(why) {
    view.innerHTML = '';
    var p = document.createElement('p');
    p.id = 'noview';
    p.textContent = why;
    view.appendChild(p);
    document.body.setAttribute('data-rendered', 'no view');
  }
  if (typeof THREE === 'undefined') { noView('No 3D view: three.js is not in this page.'); return; }
  var canvas = document.createElement('canvas');
  var context = canvas.getContext('webgl', { antialias: true }) || canvas.getContext('experimental-webgl');
  if (!context) { noView('No 3D view: this browser has no WebGL. The figures below are complete.'); return; }

  function bytes(text) {
    var s = atob(text), out = new Uint8Array(s.length);
    for (var i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
    return out.buffer;
  }
  function hex(rgb) { return 'rgb(' + rgb[0] + ',' + rgb[1] + ',' + rgb[2] + ')'; }

  var plainColours = {
    body: [0.85, 0.69, 0.58], collider: [0.62, 0.66, 0.72],
    cloth: [[0.27, 0.47, 0.67], [0.80, 0.40, 0.47], [0.13, 0.53, 0.20], [0.80, 0.73, 0.27], [0.40, 0.80, 0.93],
            [0.67, 0.20, 0.47]]
  };
  var palette = data.palette, unlabelled = data.unlabelled;
  var missing = [0.78, 0.78, 0.78];

  // Colour maps: sequential (dark blue to yellow) and diverging (red, white, blue).
  var sequential = [[0.27, 0.00, 0.33], [0.23, 0.32, 0.55], [0.13, 0.57, 0.55], [0.37, 0.79, 0.38], [0.99, 0.91, 0.14]];
  function mapSequential(t) {
    t = Math.min(1, Math.max(0, t)) * (sequential.length - 1);
    var i = Math.min(sequential.length - 2, Math.floor(t)), f = t - i, a = sequential[i], b = sequential[i + 1];
    return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f];
  }
  function mapValue(field, v) {
    if (!isFinite(v)) v = field.low;
    if (!field.diverging) return mapSequential((v - field.low) / (field.high - field.low || 1));
    var white = [0.97, 0.97, 0.97], end = v < 0 ? [0.75, 0.10, 0.10] : [0.13, 0.35, 0.75];
    var t = Math.min(1, v < 0 ? v / (field.low || -1) : v / (field.high || 1));
    return [white[0] + (end[0] - white[0]) * t, white[1] + (end[1] - white[1]) * t, white[2] + (end[2] - white[2]) * t];
  }

  var renderer = new THREE.WebGLRenderer({ canvas: canvas, context: context, antialias: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  view.appendChild(canvas);
  var scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf6f7f9);
  var camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x565a66, 0.75));
  var key = new THREE.DirectionalLight(0xffffff, 0.6);
  key.position.set(0.6, 1.0, 1.4);
  camera.add(key);  // lit from the viewer's side, whichever way the view is turned
  scene.add(camera);

  var fieldNames = [], shapeNames = data.shapes;
  var items = data.meshes.map(function (m, index) {
    var geometry = new THREE.BufferGeometry();
    var faces = new Uint32Array(bytes(m.faces));
    geometry.setIndex(new THREE.BufferAttribute(faces, 1));
    var shapes = {};
    Object.keys(m.shapes).forEach(function (name) { shapes[name] = new Float32Array(bytes(m.shapes[name])); });
    var first = m.first_shape;
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(shapes[first]), 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * m.vertices), 3));
    geometry.computeVertexNormals();
    geometry.computeBoundingBox();
    var fields = (m.fields || []).map(function (f) {
      if (fieldNames.indexOf(f.name) < 0) fieldNames.push(f.name);
      return { name: f.name, shape: f.shape, unit: f.unit, low: f.low, high: f.high, diverging: f.diverging,
               values: new Float32Array(bytes(f.values)) };
    });
    var material = new THREE.MeshStandardMaterial({
      vertexColors: THREE.VertexColors !== undefined ? THREE.VertexColors : true,
      side: THREE.DoubleSide, roughness: 0.8, metalness: 0.0,
      polygonOffset: m.role === 'body', polygonOffsetFactor: 2, polygonOffsetUnits: 8
    });
    var mesh = new THREE.Mesh(geometry, material);
    scene.add(mesh);
    var cloth = m.role === 'garment' || m.role === 'cloth';
    var plain = m.role === 'body' ? plainColours.body : m.role === 'collider' ? plainColours.collider
              : plainColours.cloth[index % plainColours.cloth.length];
    var labels = m.labels ? new Int16Array(bytes(m.labels)) : null, used = {};
    if (labels) for (var i = 0; i < labels.length; ++i) used[labels[i]] = true;  // the legend lists these
    return { data: m, mesh: mesh, geometry: geometry, shapes: shapes, fields: fields, shown: first,
             labels: labels, used: used, plain: plain, cloth: cloth };
  });

  // The view to start with may be named in the address: report.html#colour=strain&shape=placed
  // (colour: plain, parts or a colour map's name).
  var state = { shape: data.default_shape, colour: 'plain' };
  location.hash.replace(/^#/, '').split('&').forEach(function (pair) {
    var kv = pair.split('='), value = decodeURIComponent(kv[1] || '');
    if (kv[0] === 'shape' && shapeNames.indexOf(value) >= 0) state.shape = value;
    if (kv[0] === 'colour') state.colour = value === 'plain' || value === 'parts' ? value : 'field:' + value;
  });

  function colourItem(item) {
    var c = item.geometry.attributes.color.array, n = item.data.vertices, i, rgb;
    var field = null;
    if (state.colour.indexOf('field:') === 0) {
      var name = state.colour.slice(6);
      item.fields.forEach(function (f) { if (f.name === name && f.shape === item.shown) field = f; });
    }
    for (i = 0; i < n; ++i) {
      if (state.colour === 'parts' && item.labels) {
        var l = item.labels[i];
        rgb = l < 0 ? unlabelled : palette[l % palette.length];
        rgb = [rgb[0] / 255, rgb[1] / 255, rgb[2] / 255];
      } else if (field) {
        rgb = mapValue(field, field.values[i]);
      } else if (state.colour === 'plain' || (state.colour === 'parts' && !item.labels)) {
        rgb = state.colour === 'plain' ? item.plain : missing;
      } else {
        rgb = missing;
      }
      c[3 * i] = rgb[0]; c[3 * i + 1] = rgb[1]; c[3 * i + 2] = rgb[2];
    }
    item.geometry.attributes.color.needsUpdate = true;
    return field;
  }

  function setShape(item) {
    var name = item.shapes[state.shape] ? state.shape : item.data.first_shape;
    if (name === item.shown) return;
    item.geometry.attributes.position.array.set(item.shapes[name]);
    item.geometry.attributes.position.needsUpdate = true;
    item.geometry.computeVertexNormals();
    item.shown = name;
  }

  var panel = document.createElement('div');
  panel.id = 'panel';
  view.appendChild(panel);
  function group(title) {
    var f = document.createElement('fieldset'), l = document.createElement('legend');
    l.textContent = title;
    f.appendChild(l);
    panel.appendChild(f);
    return f;
  }
  function option(parent, type, name, text, checked, onChange, swatch) {
    var label = document.createElement('label'), input = document.createElement('input');
    input.type = type; input.name = name; input.checked = checked;
    input.addEventListener('change', onChange);
    label.appendChild(input);
    if (swatch) {
      var s = document.createElement('span');
      s.className = 'swatch';
      s.style.background = 'rgb(' + swatch.map(function (x) { return Math.round(255 * x); }).join(',') + ')';
      label.appendChild(s);
    }
    label.appendChild(document.createTextNode(text));
    parent.appendChild(label);
    return input;
  }

  var meshes = group('Meshes');
  items.forEach(function (item) {
    option(meshes, 'checkbox', 'mesh', item.data.name, true, function (e) {
      item.mesh.visible = e.target.checked;
      draw();
    }, item.plain);
  });
  if (shapeNames.length > 1) {
    var shapes = group('Shape');
    shapeNames.forEach(function (name) {
      option(shapes, 'radio', 'shape', name, name === state.shape, function () {
        state.shape = name;
        update();
      });
    });
  }
  var colours = group('Colour');
  var select = document.createElement('select');
  var choices = [['plain', 'plain']];
  if (items.some(function (i) { return i.labels; })) choices.push(['parts', 'parts']);
  fieldNames.forEach(function (n) { choices.push(['field:' + n, n]); });
  choices.forEach(function (c) {
    var o = document.createElement('option');
    o.value = c[0]; o.textContent = c[1];
    select.appendChild(o);
  });
  if (!choices.some(function (c) { return c[0] === state.colour; })) state.colour = 'plain';
  select.value = state.colour;
  select.addEventListener('change', function () { state.colour = select.value; update(); });
  colours.appendChild(select);
  var legend = document.createElement('div');
  legend.id = 'legend';
  colours.appendChild(legend);
  var hint = document.createElement('div');
  hint.id = 'hint';
  hint.textContent = 'drag: turn · right-drag: move · wheel: zoom';
  view.appendChild(hint);

  var svgNS = 'http://www.w3.org/2000/svg';
  function svg(tag, attributes, parent) {
    var e = document.createElementNS(svgNS, tag);
    Object.keys(attributes).forEach(function (k) { e.setAttribute(k, attributes[k]); });
    if (parent) parent.appendChild(e);
    return e;
  }
  function fmt(v) { return Math.abs(v) >= 100 ? v.toFixed(0) : Math.abs(v) >= 1 ? v.toFixed(1) : v.toPrecision(2); }

  function showLegend(field) {
    legend.innerHTML = '';
    var note = document.createElement('div');
    note.className = 'note';
    if (state.colour === 'parts') {
      var names = [];
      items.forEach(function (item) {
        if (!item.labels || !item.mesh.visible) return;
        item.data.label_names.forEach(function (n, k) {
          if (item.used[k]) names.push([item.data.name + ': ' + n, palette[k % palette.length]]);
        });
      });
      names.forEach(function (n) {
        var row = document.createElement('div'), s = document.createElement('span');
        s.className = 'swatch';
        s.style.background = hex(n[1]);
        row.appendChild(s);
        row.appendChild(document.createTextNode(n[0]));
        legend.appendChild(row);
      });
      if (items.some(function (i) { return !i.labels; })) note.textContent = 'grey: no parts for this mesh';
    } else if (field) {
      var w = 240, h = 34, box = svg('svg', { width: w, height: h, viewBox: '0 0 ' + w + ' ' + h });
      var gradient = svg('linearGradient', { id: 'dresskit-map', x1: '0', x2: '1', y1: '0', y2: '0' }, svg('defs', {}, box));
      for (var k = 0; k <= 16; ++k) {
        var v = field.low + (field.high - field.low) * k / 16;
        var rgb = mapValue(field, v).map(function (x) { return Math.round(255 * x); });
        svg('stop', { offset: (k / 16).toFixed(3), 'stop-color': hex(rgb) }, gradient);
      }
      svg('rect', { x: 4, y: 2, width: w - 8, height: 12, fill: 'url(#dresskit-map)', stroke: '#999' }, box);
      var ticks = field.diverging ? [field.low, 0, field.high] : [field.low, (field.low + field.high) / 2, field.high];
      ticks.forEach(function (v, k) {
        var t = svg('text', { x: 4 + (w - 8) * (v - field.low) / (field.high - field.low || 1), y: 28,
                              'text-anchor': k === 0 ? 'start' : k === 2 ? 'end' : 'middle' }, box);
        t.textContent = fmt(v) + (k === 2 && field.unit ? ' ' + field.unit : '');
      });
      legend.appendChild(box);
      var without = items.filter(function (i) {
        return !i.fields.some(function (f) { return f.name === field.name && f.shape === i.shown; });
      }).map(function (i) { return i.data.name; });
      note.textContent = without.length ? 'grey: ' + without.join(', ') + ' (no ' + field.name + ' map)' : '';
    } else if (state.colour.indexOf('field:') === 0) {
      note.textContent = 'No mesh has ' + state.colour.slice(6) + ' in the shape "' + state.shape + '".';
    }
    if (note.textContent) legend.appendChild(note);
  }

  function frame() {
    var box = new THREE.Box3();
    items.forEach(function (item) { box.union(item.geometry.boundingBox); });
    var centre = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3());
    // Far enough for the height and for the width at the view's aspect.
    var t = Math.tan(camera.fov * Math.PI / 360);
    var across = Math.max(size.x, size.z) * 0.5, up = size.y * 0.5;
    var distance = Math.max(up / t, across / (t * camera.aspect), 0.01) * 1.08 + 0.5 * size.z;
    camera.position.set(centre.x + 0.35 * distance, centre.y + 0.15 * distance, centre.z + 0.95 * distance);
    camera.near = distance / 100;
    camera.far = distance * 10;
    camera.updateProjectionMatrix();
    return centre;
  }
  resize();
  var controls = new THREE.OrbitControls(camera, canvas);
  controls.target.copy(frame());
  controls.update();
  controls.addEventListener('change', draw);

  function resize() {
    var w = view.clientWidth || 800, h = view.clientHeight || 500;
    renderer.setSize(w, h, false);
    canvas.style.width = w + 'px';
    canvas.style.height = h + 'px';
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  var pending = false;
  function draw() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(function () { pending = false; renderer.render(scene, camera); });
  }
  function update() {
    var field = null;
    items.forEach(function (item) {
      setShape(item);
      field = colourItem(item) || field;
    });
    showLegend(field);
    draw();
  }
  window.addEventListener('resize', function () { resize(); draw(); });

  var shown = null;
  items.forEach(function (item) { setShape(item); shown = colourItem(item) || shown; });
  showLegend(shown);
  renderer.render(scene, camera);  // the first picture now, so that it is there when the page has loaded
  document.body.setAttribute('data-rendered', 'yes');
  document.body.setAttribute('data-load-ms', performance.now().toFixed(0));
  document.body.setAttribute('data-script-ms', (performance.now() - start).toFixed(0));
})();
