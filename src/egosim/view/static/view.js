// egosim live view: draws the map and the frames the simulator streams, sends controls.
// Everything received is in SI units (m, s, rad, m/s); display converts (km/h, deg).
"use strict";

const $ = (id) => document.getElementById(id);
const KMH = 3.6;
const DEG = 180 / Math.PI;
// What is kept of each ego for its plots and trail (the server's history has the same).
const SAMPLE_FIELDS = ["x", "y", "speed", "steer", "accel_pedal", "brake_pedal", "lane_offset"];
const RETRY_MS = 2000;
const KEY_PERIOD_MS = 100;
const CTRL_KEYBOARD = 1;
const FOLLOW_SCALE = 4; // px per m when the page opens following an ego
const MIN_VEHICLE_PX = 6;
const COLOURS = {
  ground: "#2a3a2c", road: "#45494f", junction: "#4c5057", sidewalk: "#8b8f94",
  white: "#f2f2f2", yellow: "#f3c623", ego: "#3aa0ff", otherEgo: "#b07cff",
  npc: "#ff9f43", pedestrian: "#ff6fb5", obstacle: "#b5a27a", lidar: "#53f2e5",
  red: "#ff3b30", amber: "#ffcc00", green: "#34c759", off: "#5b6168", collision: "#ff2d2d",
};

const state = {
  map: null, mapError: null, frame: null, hello: null, connected: false,
  view: { cx: 0, cy: 0, scale: 4 }, follow: true, egoIndex: 0,
  // Per ego id: the last `span` s sampled every `spacing` s, as columns (t and SAMPLE_FIELDS).
  samples: new Map(), spacing: 0.1, span: 60,
  layers: {}, pointer: null, tooltip: null, keys: new Set(), errors: [],
  framesReceived: 0, firstFrameTime: null, loading: null, pageLeft: false,
};
// Page state, read by tests and handy in the console.
window.egosimView = state;

const canvas = $("world");
const ctx = canvas.getContext("2d");
let socket = null;

// ---- connection --------------------------------------------------------------------------

function connect() {
  const scheme = location.protocol === "https:" ? "wss" : "ws";
  socket = new WebSocket(`${scheme}://${location.host}/ws`);
  socket.onopen = () => { state.connected = true; setConnection("live", "live"); sendLayers(); showLoading(); };
  socket.onclose = () => {
    state.connected = false;
    if (state.pageLeft) return;
    setConnection("lost", "disconnected — retrying");
    showLoading();
    setTimeout(connect, RETRY_MS);
  };
  socket.onmessage = (event) => receive(JSON.parse(event.data));
}

function setConnection(kind, text) {
  const pill = $("connection");
  pill.className = `pill ${kind}`;
  pill.textContent = text;
}

function send(request) {
  if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(request));
}

function receive(message) {
  if (message.type === "hello") onHello(message);
  else if (message.type === "history") onHistory(message);
  else if (message.type === "frame") onFrame(message);
  else if (message.type === "graph") showNodes(message.nodes);
  else if (message.type === "reply") onReply(message);
}

function onHello(hello) {
  state.hello = hello;
  if (!hello.readonly) send({ op: "scenarios" });
}

// The map is fetched at once, beside the socket's connection; a failed fetch is retried.
function loadMap() {
  fetch("/map.json")
    .then((r) => { if (!r.ok) throw new Error(`HTTP ${r.status}`); return r.json(); })
    .then(onMap)
    .catch((error) => {
      state.mapError = String(error.message || error);
      showLoading();
      setTimeout(loadMap, RETRY_MS);
    });
}

function onMap(map) {
  state.map = map;
  state.mapError = null;
  showLoading();
  const [x0, y0, x1, y1] = map.bounds;
  state.view.cx = (x0 + x1) / 2;
  state.view.cy = (y0 + y1) / 2;
  if (state.follow) state.view.scale = FOLLOW_SCALE; else fitScale(x1 - x0, y1 - y0);
  state.mapLayer = null; // redrawn at the next frame
}

// Show the whole map (stops following).
function fitMap() {
  if (!state.map) return;
  const [x0, y0, x1, y1] = state.map.bounds;
  setFollow(false);
  const r = canvas.getBoundingClientRect();
  // The layer bar covers the top of the canvas: fit the map in the space below it.
  const top = $("layers").getBoundingClientRect().bottom - r.top + 8;
  state.view.scale = Math.max(0.05, Math.min(r.width / (x1 - x0), (r.height - top - 12) / (y1 - y0)) * 0.97);
  state.view.cx = (x0 + x1) / 2;
  state.view.cy = (y0 + y1) / 2 + top / 2 / state.view.scale;
}
window.egosimView.fitMap = fitMap;

function setFollow(on) {
  state.follow = on;
  $("follow").checked = on;
}

function fitScale(width, height) {
  const r = canvas.getBoundingClientRect();
  state.view.scale = Math.max(0.05, Math.min(r.width / width, r.height / height) * 0.95);
}

function onReply(reply) {
  if (reply.op === "scenarios" && reply.ok) {
    const select = $("scenario");
    select.length = 1;
    for (const name of reply.scenarios) select.add(new Option(name, name));
    return;
  }
  if (!reply.ok) showMessage(reply.error, true);
  else if (reply.op === "load") showMessage(`loaded ${reply.loaded}`);
  else if (reply.op === "reload") showMessage("scenario reloaded");
}

function showMessage(text, error = false) {
  const box = $("message");
  box.textContent = text;
  box.className = error ? "message error" : "message";
}

// ---- loading -----------------------------------------------------------------------------

// The steps before the page can show the simulation, each waiting, done or failed; the
// overlay lists them until all are done (and again while the connection is lost).
function loadingSteps() {
  const everConnected = state.frame !== null;
  return [
    { id: "loading-connection", done: state.connected,
      text: state.connected ? "connected to the simulator"
        : everConnected ? "connection lost, reconnecting…" : "connecting to the simulator…" },
    { id: "loading-map", done: state.map !== null, failed: state.mapError !== null,
      text: state.map ? "map loaded"
        : state.mapError ? `map not loaded (${state.mapError}), retrying…` : "loading the map…" },
    { id: "loading-frame", done: state.frame !== null,
      text: state.frame ? "first frame received" : "waiting for the first frame…" },
  ];
}

function showLoading() {
  const steps = loadingSteps();
  const waiting = steps.find((step) => !step.done);
  state.loading = waiting ? waiting.text : null;
  $("loading").hidden = !waiting;
  for (const step of steps) {
    const item = $(step.id);
    item.textContent = step.text;
    item.className = step.done ? "done" : step.failed ? "failed" : "waiting";
  }
}

// ---- frames ------------------------------------------------------------------------------

function onHistory(history) {
  state.spacing = history.spacing_s;
  state.span = history.span_s;
  plots.forEach((p) => { p.span = history.span_s; });
  state.samples = new Map(history.egos.map((ego) => [ego.id,
    Object.fromEntries(["t", ...SAMPLE_FIELDS].map((k) => [k, ego[k]]))]));
}

function onFrame(frame) {
  const previous = state.frame;
  if (previous && frame.sim_time < previous.sim_time) state.samples.clear();
  state.frame = frame;
  state.framesReceived += 1;
  if (state.firstFrameTime === null) { state.firstFrameTime = frame.sim_time; showLoading(); }
  if (state.egoIndex >= frame.egos.length) state.egoIndex = 0;
  recordSamples(frame);
  updatePanel(frame);
}

// Extend each ego's samples from the frame, one per `spacing` s, the last `span` s kept.
function recordSamples(frame) {
  const now = frame.sim_time;
  const shown = new Set(frame.egos.map((ego) => ego.id));
  for (const id of [...state.samples.keys()]) if (!shown.has(id)) state.samples.delete(id);
  for (const ego of frame.egos) {
    let store = state.samples.get(ego.id);
    if (!store) {
      store = Object.fromEntries(["t", ...SAMPLE_FIELDS].map((k) => [k, []]));
      state.samples.set(ego.id, store);
    }
    const last = store.t.length ? store.t[store.t.length - 1] : -Infinity;
    if (now - last < state.spacing - 1e-6) continue;
    store.t.push(now);
    for (const k of SAMPLE_FIELDS) store[k].push(ego[k]);
    let drop = 0;
    while (drop < store.t.length && store.t[drop] < now - state.span) drop++;
    if (drop) for (const k of ["t", ...SAMPLE_FIELDS]) store[k].splice(0, drop);
  }
}

const plots = [
  new TimePlot($("plot-speed"), "speed", "km/h", [{ label: "", colour: "#4aa8ff", key: "speed", scale: KMH }]),
  new TimePlot($("plot-steer"), "steering", "deg", [{ label: "", colour: "#c792ea", key: "steer", scale: DEG }]),
  new TimePlot($("plot-pedals"), "pedals", "0..1", [
    { label: "accel", colour: "#34c759", key: "accel_pedal" },
    { label: "brake", colour: "#ff5a5a", key: "brake_pedal" }]),
  new TimePlot($("plot-lane"), "from lane centre", "m", [{ label: "", colour: "#ffcc00", key: "lane_offset" }]),
];

// The samples of the ego the panel shows (before the first frame: the history's first).
function shownSamples() {
  const ego = state.frame && state.frame.egos[state.egoIndex];
  if (ego) return state.samples.get(ego.id) || null;
  const first = state.samples.values().next();
  return first.done ? null : first.value;
}

function updatePanel(frame) {
  $("sim-time").textContent = `${frame.sim_time.toFixed(2)} s`;
  $("rtf").textContent = frame.real_time_factor == null ? "–" : frame.real_time_factor.toFixed(2);
  $("clock-mode").textContent = frame.sync_frame == null ? frame.clock_mode : `${frame.clock_mode}, frame ${frame.sync_frame}`;
  $("run-state").textContent = frame.paused ? "paused" : "running";
  const ownsTime = frame.controls && frame.clock_mode !== "sync";
  $("pause").textContent = frame.paused ? "Resume" : "Pause";
  for (const id of ["pause", "step"]) $(id).disabled = !ownsTime;
  $("step").disabled = !ownsTime || !frame.paused;
  for (const id of ["reload", "load", "scenario", "ctrl-mode"]) $(id).disabled = !frame.controls;
  const select = $("ego-select");
  if (select.length !== frame.egos.length) {
    select.length = 0;
    frame.egos.forEach((e, i) => select.add(new Option(`ego ${e.id} · ${e.model}`, i)));
    select.value = state.egoIndex;
  }
  const ego = frame.egos[state.egoIndex];
  if (ego) {
    $("ego-speed").textContent = `${(ego.speed * KMH).toFixed(1)} km/h`;
    $("ego-gear").textContent = ego.gear;
    $("ego-steer").textContent = `${(ego.steer * DEG).toFixed(1)}°`;
    $("ego-lane").textContent = `${ego.lane_id} ${ego.lane_offset >= 0 ? "+" : ""}${ego.lane_offset.toFixed(2)} m`;
    $("ego-accel").style.width = `${(100 * ego.accel_pedal).toFixed(0)}%`;
    $("ego-brake").style.width = `${(100 * ego.brake_pedal).toFixed(0)}%`;
    if (document.activeElement !== $("ctrl-mode")) $("ctrl-mode").value = String(ego.ctrl_mode);
    $("keyboard-hint").hidden = ego.ctrl_mode !== CTRL_KEYBOARD;
  }
  const banner = $("banner");
  banner.hidden = !frame.collisions.length;
  banner.textContent = frame.collisions.length ? `collision at ${frame.collisions[0].t.toFixed(2)} s` : "";
  showReplay(frame.replay);
  showImages(frame.images);
}

function showReplay(replay) {
  $("replay").hidden = !replay;
  if (!replay) return;
  const slider = $("replay-position");
  slider.max = replay.duration;
  if (document.activeElement !== slider) slider.value = replay.position;
  $("replay-time").textContent = `${replay.position.toFixed(1)} / ${replay.duration.toFixed(1)} s`;
  const playing = replay.mode === "replay" && replay.status === "running";
  $("replay-toggle").textContent = playing ? "Pause" : "Play";
  $("replay-toggle").dataset.action = playing ? "pause" : "play";
}

function showImages(images) {
  $("images").hidden = !images.length;
  const list = $("image-list");
  images.forEach((image, i) => {
    let img = list.children[i];
    if (!img) { img = document.createElement("img"); list.appendChild(img); }
    img.alt = image.name;
    img.title = `${image.name} at ${image.stamp.toFixed(2)} s`;
    img.src = `data:${image.mime};base64,${image.data}`;
  });
  while (list.children.length > images.length) list.lastChild.remove();
}

function showNodes(nodes) {
  const list = $("nodes");
  list.replaceChildren(...nodes.map((node) => {
    const item = document.createElement("li");
    const name = document.createElement("div");
    name.className = "name";
    name.textContent = node.name;
    const topics = document.createElement("div");
    topics.className = "topics";
    topics.textContent = `pub: ${node.publishes.join(", ") || "–"} · sub: ${node.subscribes.join(", ") || "–"}`;
    item.append(name, topics);
    return item;
  }));
}

// ---- drawing -----------------------------------------------------------------------------

function worldToScreen(x, y) {
  const r = canvas.getBoundingClientRect();
  const v = state.view;
  return [r.width / 2 + (x - v.cx) * v.scale, r.height / 2 - (y - v.cy) * v.scale];
}
window.egosimView.worldToScreen = worldToScreen;

function screenToWorld(px, py) {
  const r = canvas.getBoundingClientRect();
  const v = state.view;
  return [v.cx + (px - r.width / 2) / v.scale, v.cy - (py - r.height / 2) / v.scale];
}

// Draw in metres: x east, y north.
function worldTransform(g) {
  const r = canvas.getBoundingClientRect();
  const ratio = window.devicePixelRatio || 1;
  const v = state.view;
  g.setTransform(ratio * v.scale, 0, 0, -ratio * v.scale,
    ratio * (r.width / 2 - v.cx * v.scale), ratio * (r.height / 2 + v.cy * v.scale));
}

function polyline(g, points) {
  g.beginPath();
  points.forEach(([x, y], i) => (i ? g.lineTo(x, y) : g.moveTo(x, y)));
}

function polylineXY(g, xs, ys) {
  g.beginPath();
  xs.forEach((x, i) => (i ? g.lineTo(x, ys[i]) : g.moveTo(x, ys[i])));
}

function drawMap(g, map) {
  const px = 1 / state.view.scale;
  g.lineJoin = "round";
  g.strokeStyle = COLOURS.sidewalk; g.lineWidth = 2.0;
  for (const walk of map.sidewalks) { polyline(g, walk); g.stroke(); }
  for (const lane of map.lanes) {
    g.fillStyle = lane.junction ? COLOURS.junction : COLOURS.road;
    g.strokeStyle = g.fillStyle; g.lineWidth = 0.08;
    polyline(g, lane.outline); g.closePath(); g.fill(); g.stroke();
  }
  for (const c of map.crosswalks) drawCrosswalk(g, c);
  if (state.layers.markings) {
    for (const m of map.markings) {
      g.strokeStyle = m.color === "yellow" ? COLOURS.yellow : COLOURS.white;
      g.lineWidth = m.double ? Math.max(0.35, 2.4 * px) : Math.max(0.15, 1.2 * px);
      g.setLineDash(m.style === "dashed" ? [3, 5] : []);
      polyline(g, m.points); g.stroke();
    }
    g.setLineDash([]);
    g.strokeStyle = COLOURS.white; g.lineWidth = Math.max(0.4, 1.5 * px);
    for (const line of map.stop_lines) { polyline(g, line); g.stroke(); }
  }
}

function drawCrosswalk(g, c) {
  const [x0, y0] = c.start, [x1, y1] = c.end;
  const length = Math.hypot(x1 - x0, y1 - y0);
  if (length < 0.1) return;
  const ux = (x1 - x0) / length, uy = (y1 - y0) / length;
  const nx = -uy * c.width / 2, ny = ux * c.width / 2;
  g.fillStyle = "rgba(242,242,242,0.85)";
  for (let s = 0.25; s + 0.5 <= length; s += 1.0) {
    const ax = x0 + ux * s, ay = y0 + uy * s, bx = ax + ux * 0.5, by = ay + uy * 0.5;
    g.beginPath();
    g.moveTo(ax + nx, ay + ny); g.lineTo(bx + nx, by + ny); g.lineTo(bx - nx, by - ny); g.lineTo(ax - nx, ay - ny);
    g.fill();
  }
}

function lampColour(aspect) {
  const bits = state.map.aspect_bits;
  if (aspect === state.map.aspect_off || aspect <= 0) return COLOURS.off;
  if (aspect & bits.red) return COLOURS.red;
  if (aspect & bits.yellow) return COLOURS.amber;
  if (aspect & (bits.green | bits.left)) return COLOURS.green;
  return COLOURS.off;
}
// The colour a light is drawn in now (tests read it).
window.egosimView.lightColour = (id) => {
  const k = state.map ? state.map.lights.findIndex((light) => light.id === id) : -1;
  return k < 0 || !state.frame ? null : lampColour(state.frame.light_aspects[k]);
};

function drawLights(g, frame) {
  const radius = Math.max(0.8, 3.5 / state.view.scale);
  const bits = state.map.aspect_bits;
  state.map.lights.forEach((light, k) => {
    const aspect = frame.light_aspects[k];
    const [x, y] = light.position;
    g.fillStyle = "#111"; g.beginPath(); g.arc(x, y, radius * 1.35, 0, 2 * Math.PI); g.fill();
    g.fillStyle = lampColour(aspect); g.beginPath(); g.arc(x, y, radius, 0, 2 * Math.PI); g.fill();
    if (aspect > 0 && (aspect & bits.left) && (aspect & (bits.red | bits.yellow))) {
      g.fillStyle = COLOURS.green; g.beginPath(); g.arc(x, y, radius * 0.45, 0, 2 * Math.PI); g.fill();
    }
  });
}

function box(g, x, y, yaw, length, width, fill, outline) {
  // Never smaller than a few pixels, so traffic stays visible on a whole-town view.
  length = Math.max(length, MIN_VEHICLE_PX / state.view.scale);
  width = Math.max(width, (MIN_VEHICLE_PX / 2) / state.view.scale);
  g.save();
  g.translate(x, y); g.rotate(yaw);
  g.fillStyle = fill; g.fillRect(-length / 2, -width / 2, length, width);
  if (outline) { g.strokeStyle = outline; g.lineWidth = Math.max(0.1, 1 / state.view.scale); g.strokeRect(-length / 2, -width / 2, length, width); }
  g.restore();
}

function drawObjects(g, frame) {
  const o = frame.objects, kinds = state.map.object_kinds;
  for (let k = 0; k < o.id.length; k++) {
    const kind = o.kind[k];
    if (kind === kinds.pedestrian) {
      if (!state.layers.pedestrians) continue;
      g.fillStyle = COLOURS.pedestrian; g.beginPath();
      g.arc(o.x[k], o.y[k], Math.max(0.4, 3 / state.view.scale), 0, 2 * Math.PI); g.fill();
    } else if (kind === kinds.obstacle) {
      if (state.layers.obstacles) box(g, o.x[k], o.y[k], o.yaw[k], o.length[k], o.width[k], COLOURS.obstacle, "#222");
    } else if (state.layers.npcs) {
      box(g, o.x[k], o.y[k], o.yaw[k], o.length[k], o.width[k], COLOURS.npc, "#5a3000");
    }
  }
}

function drawEgos(g, frame) {
  if (state.layers.trails) {
    g.lineWidth = Math.max(0.3, 2 / state.view.scale);
    frame.egos.forEach((ego, i) => {
      const trail = state.samples.get(ego.id);
      if (!trail || trail.t.length < 2) return;
      g.strokeStyle = i === state.egoIndex ? "rgba(58,160,255,0.7)" : "rgba(176,124,255,0.6)";
      polylineXY(g, trail.x, trail.y); g.lineTo(ego.x, ego.y); g.stroke();
    });
  }
  frame.egos.forEach((ego, i) => {
    const c = Math.cos(ego.yaw), s = Math.sin(ego.yaw);
    const cx = ego.x + c * ego.centre_offset, cy = ego.y + s * ego.centre_offset;
    const colour = i === state.egoIndex ? COLOURS.ego : COLOURS.otherEgo;
    if (state.view.scale < 2) { // a halo finds the ego on a zoomed-out view
      g.strokeStyle = colour; g.lineWidth = 2 / state.view.scale;
      g.beginPath(); g.arc(cx, cy, 9 / state.view.scale, 0, 2 * Math.PI); g.stroke();
    }
    box(g, cx, cy, ego.yaw, ego.length, ego.width, colour, "#ffffff");
    // Heading: a white chevron at the front.
    g.save(); g.translate(cx, cy); g.rotate(ego.yaw);
    g.fillStyle = "#ffffff"; g.beginPath();
    g.moveTo(ego.length / 2, 0); g.lineTo(ego.length / 2 - 1.2, ego.width * 0.35); g.lineTo(ego.length / 2 - 1.2, -ego.width * 0.35);
    g.closePath(); g.fill(); g.restore();
  });
}

function drawCollisions(g, frame) {
  const on = Math.floor(performance.now() / 200) % 2 === 0;
  for (const c of frame.collisions) {
    g.strokeStyle = COLOURS.collision; g.lineWidth = Math.max(0.3, 3 / state.view.scale);
    g.globalAlpha = on ? 1 : 0.35;
    g.beginPath(); g.arc(c.x, c.y, Math.max(3, 14 / state.view.scale), 0, 2 * Math.PI); g.stroke();
    g.globalAlpha = 1;
  }
}

function drawLidar(g, frame) {
  if (!frame.lidar) return;
  const size = Math.max(0.15, 1.5 / state.view.scale);
  g.fillStyle = COLOURS.lidar;
  for (let k = 0; k + 1 < frame.lidar.length; k += 2) g.fillRect(frame.lidar[k] - size / 2, frame.lidar[k + 1] - size / 2, size, size);
}

function drawLabels(frame) {
  if (!state.layers.labels || state.view.scale < 2.5) return;
  ctx.font = "11px system-ui, sans-serif";
  ctx.textAlign = "center";
  const label = (text, x, y) => {
    const [px, py] = worldToScreen(x, y);
    ctx.lineWidth = 3; ctx.strokeStyle = "rgba(0,0,0,0.7)"; ctx.strokeText(text, px, py - 12);
    ctx.fillStyle = "#fff"; ctx.fillText(text, px, py - 12);
  };
  frame.egos.forEach((e) => label(`ego ${e.id}`, e.x, e.y));
  const o = frame.objects;
  for (let k = 0; k < o.id.length; k++) if (visibleKind(o.kind[k])) label(String(o.id[k]), o.x[k], o.y[k]);
}

function visibleKind(kind) {
  const kinds = state.map.object_kinds;
  if (kind === kinds.pedestrian) return state.layers.pedestrians;
  if (kind === kinds.obstacle) return state.layers.obstacles;
  return state.layers.npcs;
}

function draw() {
  const r = canvas.getBoundingClientRect();
  const ratio = window.devicePixelRatio || 1;
  if (canvas.width !== Math.round(r.width * ratio) || canvas.height !== Math.round(r.height * ratio)) {
    canvas.width = Math.round(r.width * ratio); canvas.height = Math.round(r.height * ratio);
  }
  const frame = state.frame;
  if (state.follow && frame && frame.egos[state.egoIndex]) {
    state.view.cx = frame.egos[state.egoIndex].x; state.view.cy = frame.egos[state.egoIndex].y;
  }
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = COLOURS.ground; ctx.fillRect(0, 0, canvas.width, canvas.height);
  if (state.map) {
    worldTransform(ctx);
    drawMap(ctx, state.map);
    if (frame) {
      if (state.layers.lidar) drawLidar(ctx, frame);
      drawObjects(ctx, frame);
      drawEgos(ctx, frame);
      if (state.layers.lights) drawLights(ctx, frame);
      drawCollisions(ctx, frame);
      ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
      drawLabels(frame);
    }
  }
  $("scale").textContent = `${(100 / state.view.scale).toFixed(0)} m per 100 px`;
  showTooltip();
  const samples = shownSamples();
  plots.forEach((p) => p.draw(samples));
  requestAnimationFrame(draw);
}

// ---- interaction -------------------------------------------------------------------------

let drag = null;
canvas.addEventListener("mousedown", (e) => { drag = [e.clientX, e.clientY]; canvas.focus(); });
window.addEventListener("mouseup", () => { drag = null; });
canvas.addEventListener("mousemove", (e) => {
  if (drag) {
    const [dx, dy] = [e.clientX - drag[0], e.clientY - drag[1]];
    if (dx || dy) setFollow(false);
    state.view.cx -= dx / state.view.scale; state.view.cy += dy / state.view.scale;
    drag = [e.clientX, e.clientY];
  }
  const rect = canvas.getBoundingClientRect();
  state.pointer = [e.clientX - rect.left, e.clientY - rect.top];
  showTooltip();
});
canvas.addEventListener("mouseleave", () => { state.pointer = null; showTooltip(); });
canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  const rect = canvas.getBoundingClientRect();
  const [mx, my] = [e.clientX - rect.left, e.clientY - rect.top];
  const before = screenToWorld(mx, my);
  state.view.scale = Math.min(80, Math.max(0.05, state.view.scale * Math.exp(-e.deltaY * 0.0015)));
  if (!state.follow) {
    const after = screenToWorld(mx, my);
    state.view.cx += before[0] - after[0]; state.view.cy += before[1] - after[1];
  }
}, { passive: false });

// What is under the pointer (canvas px): its description, or null.
function thingAt(px, py) {
  const frame = state.frame;
  if (!frame || !state.map) return null;
  const [wx, wy] = screenToWorld(px, py);
  const reach = Math.max(1.5, 8 / state.view.scale);
  let best = null, bestD = Infinity;
  const consider = (text, x, y, size) => {
    const d = Math.hypot(x - wx, y - wy);
    if (d < Math.max(reach, size / 2) && d < bestD) { best = text; bestD = d; }
  };
  const names = Object.fromEntries(Object.entries(state.map.object_kinds).map(([n, v]) => [v, n.replace("_", " ")]));
  frame.egos.forEach((g) => consider(`ego ${g.id} · ${(g.speed * KMH).toFixed(1)} km/h · ${g.gear}`, g.x, g.y, g.length));
  const o = frame.objects;
  for (let k = 0; k < o.id.length; k++) {
    if (visibleKind(o.kind[k])) consider(`${names[o.kind[k]]} ${o.id[k]} · ${(o.speed[k] * KMH).toFixed(1)} km/h`, o.x[k], o.y[k], o.length[k]);
  }
  if (state.layers.lights) {
    for (const light of state.map.lights) consider(`light ${light.id}`, light.position[0], light.position[1], 2);
  }
  return best;
}

// The tooltip, for what is under the pointer now: run when the mouse moves and at every
// redraw, so it follows what moves under a still mouse and goes when that has driven off.
function showTooltip() {
  const tip = $("tooltip");
  const text = state.pointer && !drag ? thingAt(...state.pointer) : null;
  state.tooltip = text;
  tip.hidden = text === null;
  if (text !== null) {
    if (tip.textContent !== text) tip.textContent = text;
    tip.style.left = `${state.pointer[0] + 14}px`; tip.style.top = `${state.pointer[1] + 10}px`;
  }
}

// Keyboard driving: the held keys go to the simulator every KEY_PERIOD_MS while the
// followed ego is in keyboard mode; it brakes by itself when they stop coming.
const KEY_ROLES = {
  ArrowUp: "throttle", KeyW: "throttle", ArrowDown: "brake", KeyS: "brake",
  ArrowLeft: "left", KeyA: "left", ArrowRight: "right", KeyD: "right",
};
function keyboardDriving() {
  const ego = state.frame && state.frame.egos[state.egoIndex];
  return Boolean(ego && ego.ctrl_mode === CTRL_KEYBOARD && state.frame.controls);
}
window.addEventListener("keydown", (e) => {
  if (e.target.tagName === "SELECT" || e.target.tagName === "INPUT") return;
  const role = KEY_ROLES[e.code];
  if (role && keyboardDriving()) { state.keys.add(role); e.preventDefault(); sendKeys(); }
});
window.addEventListener("keyup", (e) => {
  const role = KEY_ROLES[e.code];
  if (role) { state.keys.delete(role); if (keyboardDriving()) sendKeys(); }
});
window.addEventListener("blur", () => state.keys.clear());
function sendKeys() {
  const held = Object.fromEntries(["throttle", "brake", "left", "right"].map((k) => [k, state.keys.has(k)]));
  send({ op: "keys", ego: state.egoIndex, ...held });
}
setInterval(() => { if (keyboardDriving() && document.visibilityState === "visible") sendKeys(); }, KEY_PERIOD_MS);

// ---- controls ----------------------------------------------------------------------------

$("pause").addEventListener("click", () => send({ op: state.frame && state.frame.paused ? "resume" : "pause" }));
$("step").addEventListener("click", () => send({ op: "step" }));
$("reload").addEventListener("click", () => send({ op: "reload" }));
$("load").addEventListener("click", () => {
  const name = $("scenario").value;
  if (name) send({ op: "load", name }); else showMessage("choose a scenario first", true);
});
$("ctrl-mode").addEventListener("change", (e) => {
  send({ op: "ctrl_mode", ego: state.egoIndex, mode: Number(e.target.value) });
  canvas.focus();
});
$("ego-select").addEventListener("change", (e) => {
  state.egoIndex = Number(e.target.value);
  setFollow(true);
});
$("follow").addEventListener("change", (e) => { state.follow = e.target.checked; });
$("fit").addEventListener("click", fitMap);
$("replay-toggle").addEventListener("click", (e) => send({ op: "replay", action: e.target.dataset.action || "play" }));
$("replay-position").addEventListener("change", (e) => send({ op: "replay", action: "seek", position: Number(e.target.value) }));

function sendLayers() { send({ op: "layers", lidar: Boolean(state.layers.lidar) }); }
for (const box of document.querySelectorAll("#layers input")) {
  state.layers[box.dataset.layer] = box.checked;
  box.addEventListener("change", () => {
    state.layers[box.dataset.layer] = box.checked;
    if (box.dataset.layer === "lidar") sendLayers();
  });
}

// Leaving the page closes its socket: a page kept frozen in the browser's back-forward
// cache would otherwise stop reading it, and the server would wait on it. Coming back
// connects again.
window.addEventListener("pagehide", () => { state.pageLeft = true; if (socket) socket.close(1000, "page left"); });
window.addEventListener("pageshow", (e) => { if (e.persisted) { state.pageLeft = false; connect(); } });

window.addEventListener("error", (e) => state.errors.push(String(e.message)));
showLoading();
loadMap();
connect();
requestAnimationFrame(draw);
