// RoboMW console page: plain JavaScript and SVG, no libraries, nothing loaded from elsewhere.
// The server pushes JSON updates over the WebSocket /live (see ConsoleView.update); this script
// keeps a model, redraws what changed, and sends retract / dispose / stop requests (PageRequest).
"use strict";

const SVG = "http://www.w3.org/2000/svg";
const PALETTE = ["#d1495b", "#2e86ab", "#3b9c4f", "#edae49", "#7d5ba6", "#00798c", "#e07a2f", "#6c757d"];
const STALE_POSE_SECONDS = 3;
const ALTITUDE_SHOWN_METRES = 0.05; // a flyer's altitude is shown beside its name above this
const MAX_EVENTS_SHOWN = 300;

const token = new URLSearchParams(location.hash.replace(/^#/, "")).get("token") || "";
const model = { world: null, robots: new Map(), hosts: [], now: 0, controls: { agents: false, robots: false, agentsWhyNot: "" }, connected: false };
const trails = new Map(); // robot -> [[t, x, y], ...]
let socket = null;
let retryMillis = 500;
let requestId = 0;
const pending = new Map();

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === "class") e.className = v; else if (k === "style") e.style.cssText = v; else if (k.startsWith("on")) e.addEventListener(k.slice(2), v); else if (v !== undefined && v !== null) e.setAttribute(k, v);
  }
  for (const c of children) if (c !== null && c !== undefined) e.append(c.nodeType ? c : String(c));
  return e;
}
function svg(tag, attrs) {
  const e = document.createElementNS(SVG, tag);
  // Styles through the CSSOM: the page's Content-Security-Policy allows no inline style attributes.
  for (const [k, v] of Object.entries(attrs || {})) if (k === "style") e.style.cssText = v; else e.setAttribute(k, v);
  return e;
}
function num(v, digits) { return Number(v).toFixed(digits); }
function ago(seconds) {
  if (!isFinite(seconds) || seconds < 0) return "never";
  if (seconds < 90) return Math.round(seconds) + " s ago";
  if (seconds < 5400) return Math.round(seconds / 60) + " min ago";
  return Math.round(seconds / 3600) + " h ago";
}
function shortId(id) { return id.slice(0, 8); }
function simpleName(cls) { return (cls || "").split(".").pop(); }
function colorOf(name) {
  const names = [...model.robots.keys()];
  const i = model.world ? model.world.robots.findIndex(r => r.name === name) : -1;
  return PALETTE[(i >= 0 ? i : names.indexOf(name)) % PALETTE.length];
}

// ---- connection ----

function connect() {
  const scheme = location.protocol === "https:" ? "wss:" : "ws:";
  socket = new WebSocket(scheme + "//" + location.host + "/live");
  socket.onopen = () => { retryMillis = 500; setLink(true); };
  socket.onmessage = (m) => {
    const data = JSON.parse(m.data);
    if (data.type === "update") apply(data); else if (data.type === "reply") replied(data);
  };
  socket.onclose = () => {
    setLink(false);
    setTimeout(connect, retryMillis);
    retryMillis = Math.min(5000, retryMillis * 2);
  };
}

function setLink(up) {
  model.connected = up;
  const b = document.getElementById("link");
  b.textContent = up ? "live" : "disconnected: reconnecting…";
  b.className = "badge " + (up ? "live" : "down");
  b.dataset.state = up ? "live" : "disconnected";
  document.body.classList.toggle("offline", !up);
  if (!up) { trails.clear(); renderAll(); }
}

function send(request, label) {
  if (!socket || socket.readyState !== WebSocket.OPEN) { toast(label + ": not connected", true); return; }
  request.id = ++requestId;
  request.token = token;
  pending.set(request.id, label);
  socket.send(JSON.stringify(request));
}

function replied(r) {
  const label = pending.get(r.id) || r.op || "request";
  pending.delete(r.id);
  toast(label + ": " + r.message, !r.ok);
}

function toast(text, bad) {
  const box = document.getElementById("toast");
  const d = el("div", { class: bad ? "bad" : "" }, text);
  box.append(d);
  setTimeout(() => d.remove(), 8000);
}

// ---- model ----

function apply(u) {
  model.now = u.now;
  model.controls = u.controls;
  document.getElementById("title").textContent = u.title || "";
  if ("world" in u) { model.world = u.world; }
  for (const r of u.robots) {
    model.robots.set(r.name, r);
    if (r.trailReset || !trails.has(r.name)) trails.set(r.name, []);
    const t = trails.get(r.name);
    for (const p of r.trail) t.push(p);
  }
  model.hosts = u.hosts;
  for (const e of u.events) addEvent(e);
  renderAll();
}

// The side panels are redrawn only when what they show changed, so a button stays put under the pointer.
let drawnRobots = "", drawnHosts = "";
function renderAll() {
  renderMap();
  const robots = JSON.stringify([...model.robots.values()].map(r => [r, Math.round(model.now)])) + model.connected + JSON.stringify(model.controls);
  if (robots !== drawnRobots) { drawnRobots = robots; renderRobots(); }
  const hosts = JSON.stringify(model.hosts) + model.connected + JSON.stringify(model.controls) + Math.round(model.now);
  if (hosts !== drawnHosts) { drawnHosts = hosts; renderHosts(); }
}

// ---- the map ----

function bounds() {
  const w = model.world;
  if (w) {
    const m = w.walls ? w.wallThickness : 0;
    return { minX: -m, minY: -m, maxX: w.width + m, maxY: w.height + m };
  }
  let b = null;
  for (const [, t] of trails) for (const p of t) {
    if (!b) b = { minX: p[1], minY: p[2], maxX: p[1], maxY: p[2] };
    b.minX = Math.min(b.minX, p[1]); b.minY = Math.min(b.minY, p[2]); b.maxX = Math.max(b.maxX, p[1]); b.maxY = Math.max(b.maxY, p[2]);
  }
  if (!b) return { minX: -1, minY: -1, maxX: 1, maxY: 1 };
  return { minX: b.minX - 0.5, minY: b.minY - 0.5, maxX: b.maxX + 0.5, maxY: b.maxY + 0.5 };
}

function renderMap() {
  const map = document.getElementById("map");
  const b = bounds();
  const sy = (y) => b.maxY - y; // world y up, SVG y down
  map.setAttribute("viewBox", [b.minX, 0, b.maxX - b.minX, b.maxY - b.minY].map(v => num(v, 3)).join(" "));
  map.replaceChildren();
  const w = model.world;
  document.getElementById("world-name").textContent = w ? w.name : "";
  document.getElementById("map-note").textContent = w ? (num(w.width, 2) + " × " + num(w.height, 2) + " m") : "No world map: robots are drawn where they report themselves (start the console with --world to see the arena).";
  if (w) {
    if (w.walls) map.append(svg("rect", { class: "wall", x: b.minX, y: 0, width: b.maxX - b.minX, height: b.maxY - b.minY }));
    map.append(svg("rect", { class: "arena", x: 0, y: sy(w.height), width: w.width, height: w.height, style: "fill:" + grey(w.floorBrightness) }));
    for (const area of (w.water || [])) map.append(svg("polygon", { class: "water", points: area.map(p => num(p[0], 3) + "," + num(sy(p[1]), 3)).join(" ") }));
    for (const p of w.patches) map.append(svg("rect", { x: p.x, y: sy(p.y + p.height), width: p.width, height: p.height, style: "fill:" + grey(p.brightness) }));
    for (const o of w.obstacles) map.append(obstacle(o, sy));
  } else {
    drawGrid(map, b, sy);
  }
  for (const [name, t] of trails) {
    if (t.length < 2) continue;
    map.append(svg("polyline", { class: "trail", stroke: colorOf(name), points: t.map(p => num(p[1], 3) + "," + num(sy(p[2]), 3)).join(" ") }));
  }
  for (const [name, r] of model.robots) {
    if (!r.pose) continue;
    const mark = w && w.robots.find(m => m.name === name);
    const len = mark ? mark.length : 0.2, wid = mark ? mark.width : 0.15;
    const stale = !r.reachable || !model.connected || (model.now - r.pose.t) > STALE_POSE_SECONDS && !r.pose.truth;
    const g = svg("g", { id: "robot-" + name, class: "robot" + (stale ? " stale" : ""), "data-x": num(r.pose.x, 4), "data-y": num(r.pose.y, 4),
      transform: "translate(" + num(r.pose.x, 4) + " " + num(sy(r.pose.y), 4) + ") rotate(" + num(-r.pose.heading * 180 / Math.PI, 2) + ")" });
    g.append(svg("rect", { class: "robot-body", x: -len / 2, y: -wid / 2, width: len, height: wid, rx: 0.015, style: "fill:" + colorOf(name) }));
    g.append(svg("polygon", { class: "robot-nose", points: [len / 2 - 0.05, -wid / 4, len / 2 - 0.01, 0, len / 2 - 0.05, wid / 4].map(v => num(v, 3)).join(" ") }));
    map.append(g);
    const label = svg("text", { class: "label", x: num(r.pose.x + len * 0.6, 3), y: num(sy(r.pose.y) - wid * 0.6, 3) });
    const flying = (r.pose.z || 0) > ALTITUDE_SHOWN_METRES;
    label.textContent = name + (flying ? " ↑" + num(r.pose.z, 1) + " m" : "") + (stale ? " (stale)" : "");
    if (flying) g.setAttribute("data-z", num(r.pose.z, 3));
    map.append(label);
  }
}

function grey(brightness) { const v = Math.round(255 * Math.max(0, Math.min(1, brightness))); return "rgb(" + v + "," + v + "," + v + ")"; }

function obstacle(o, sy) {
  if (o.kind === "circle") return svg("circle", { class: "obstacle", cx: o.x, cy: sy(o.y), r: o.width / 2 });
  if (o.kind === "polygon") return svg("polygon", { class: "obstacle", points: o.points.map(p => p[0] + "," + sy(p[1])).join(" ") });
  return svg("rect", { class: "obstacle", x: -o.width / 2, y: -o.height / 2, width: o.width, height: o.height,
    transform: "translate(" + o.x + " " + sy(o.y) + ") rotate(" + num(-o.angle * 180 / Math.PI, 2) + ")" });
}

function drawGrid(map, b, sy) {
  for (let x = Math.ceil(b.minX); x <= b.maxX; x++) map.append(svg("line", { x1: x, x2: x, y1: 0, y2: b.maxY - b.minY, stroke: "#e3e6ea", "stroke-width": 0.01 }));
  for (let y = Math.ceil(b.minY); y <= b.maxY; y++) map.append(svg("line", { x1: b.minX, x2: b.maxX, y1: sy(y), y2: sy(y), stroke: "#e3e6ea", "stroke-width": 0.01 }));
}

// ---- robots ----

function renderRobots() {
  const box = document.getElementById("robots");
  if (model.robots.size === 0) return;
  box.replaceChildren();
  for (const [name, r] of model.robots) {
    const age = r.pose ? model.now - r.pose.t : Infinity;
    const stale = !r.reachable || !model.connected;
    const badge = !model.connected ? el("span", { class: "badge stale" }, "stale")
      : !r.reachable ? el("span", { class: "badge down" }, "unreachable") : el("span", { class: "badge up" }, "live");
    const stop = el("button", { class: "danger", "data-action": "stop", "data-robot": name, onclick: () => send({ op: "stop", robot: name }, "stop " + name) }, "Stop");
    const stoppable = (model.controls.stoppable || []).includes(name);
    stop.disabled = !stoppable || !token || !model.connected;
    stop.title = !stoppable ? "this console does not drive " + name + " (it is driven through its brick by another process)"
      : !token ? "open the address the console printed: it carries the access token" : "stop every motor of " + name;
    const kv = el("dl", { class: "kv" });
    if (r.pose) {
      kv.append(el("dt", {}, r.pose.truth ? "pose (true)" : "pose (odometry)"), el("dd", { "data-field": "pose" },
        "x " + num(r.pose.x, 3) + " m, y " + num(r.pose.y, 3) + " m, " + ((r.pose.z || 0) > ALTITUDE_SHOWN_METRES ? "z " + num(r.pose.z, 2) + " m, " : "") + num(r.pose.heading * 180 / Math.PI, 1) + "°" + (stale ? " (" + ago(age) + ")" : "")));
    }
    if (r.lastCommand) kv.append(el("dt", {}, "last command"), el("dd", {}, r.lastCommand + " (" + ago(model.now - r.commandTime) + ")"));
    if (r.source) kv.append(el("dt", {}, "reached at"), el("dd", { class: "addr" }, r.source));
    if (r.detail) kv.append(el("dt", {}, "problem"), el("dd", {}, r.detail));
    const sensors = el("div", { class: "sensors" });
    for (const [sname, s] of Object.entries(r.sensors)) sensors.append(sparkline(sname, s));
    box.append(el("div", { class: "card" + (stale ? " stale" : ""), "data-robot": name },
      el("h3", {}, el("span", { style: "color:" + colorOf(name) }, "■"), name, badge, stop), kv, sensors));
  }
}

function sparkline(name, s) {
  const values = s.values;
  const last = values.length ? values[values.length - 1][1] : NaN;
  const chart = svg("svg", { viewBox: "0 0 100 30", preserveAspectRatio: "none" });
  if (values.length > 1) {
    const t0 = values[0][0], t1 = values[values.length - 1][0] || t0 + 1;
    let lo = Math.min(...values.map(v => v[1])), hi = Math.max(...values.map(v => v[1]));
    if (hi - lo < 1e-9) { lo -= 1; hi += 1; }
    chart.append(svg("polyline", { points: values.map(v => num(100 * (v[0] - t0) / Math.max(1e-9, t1 - t0), 2) + "," + num(28 - 26 * (v[1] - lo) / (hi - lo), 2)).join(" ") }));
  }
  return el("div", { class: "sensor", "data-sensor": name }, name + ": ", el("b", {}, isFinite(last) ? num(last, 3) : "–"), " " + s.unit, chart);
}

// ---- hosts and agents ----

function renderHosts() {
  const box = document.getElementById("hosts");
  if (model.hosts.length === 0) return;
  box.replaceChildren();
  for (const h of model.hosts) {
    const stale = !h.up || !model.connected;
    const since = h.lastContactNanos ? model.now - h.lastContactNanos / 1e9 : Infinity;
    const badge = h.up && model.connected ? el("span", { class: "badge up" }, "up") : el("span", { class: "badge down" }, h.up ? "stale" : "down");
    const kv = el("dl", { class: "kv" },
      el("dt", {}, "robot"), el("dd", { "data-field": "robot" }, h.robot === null ? "(not reported)" : h.robot || "none"),
      el("dt", {}, "agents"), el("dd", { "data-field": "agent-count" }, String(h.agents.length) + (stale ? " (as last seen, " + ago(since) + ")" : "")),
      el("dt", {}, "owed deliveries"), el("dd", { "data-field": "owed" }, owedText(h)));
    if (!h.up) kv.append(el("dt", {}, "problem"), el("dd", {}, h.error || "no answer"));
    const agents = el("div", { class: stale ? "stale-block" : "" });
    for (const a of h.agents) agents.append(agentView(a, h, stale));
    box.append(el("div", { class: "card host" + (stale ? " stale" : ""), "data-host": h.name, "data-up": String(h.up) },
      el("h3", {}, h.name, badge, el("span", { class: "addr" }, h.address)), kv, agents));
  }
}

function owedText(h) {
  if (h.owed === null || h.owed === undefined) return "not reported by this host";
  if (h.owed.length === 0) return "none";
  return h.owed.map(o => o.count + " to " + o.home + " (oldest " + ago(model.now - o.oldestNanos / 1e9) + ")").join("; ");
}

function agentView(a, h, stale) {
  const stops = el("ol", { class: "stops" });
  if (a.itinerary) {
    a.itinerary.forEach((s, i) => {
      const cls = i === a.currentStop ? "here" : s.outcome ? s.outcome : "next";
      stops.append(el("li", { class: cls, title: s.detail || s.outcome || "ahead" }, hostName(s.host) + (s.outcome ? " " + mark(s.outcome) : "")));
    });
  }
  const can = model.controls.agents && token && model.connected && h.up;
  const why = !model.controls.agents ? model.controls.agentsWhyNot : !token ? "open the address the console printed: it carries the access token" : !h.up ? "the host is down" : "";
  const retract = el("button", { "data-action": "retract", onclick: () => send({ op: "retract", agent: a.id }, "retract " + shortId(a.id)) }, "Retract");
  const dispose = el("button", { class: "danger", "data-action": "dispose", onclick: () => send({ op: "dispose", agent: a.id }, "dispose " + shortId(a.id)) }, "Dispose");
  retract.disabled = dispose.disabled = !can;
  retract.title = dispose.title = why;
  return el("div", { class: "agent", "data-agent": a.id, "data-status": a.status },
    el("div", {}, el("b", {}, simpleName(a.className)), " ", el("span", { class: "id" }, shortId(a.id)), " · ", a.status,
      " · home ", el("span", { class: "addr" }, hostName(a.home)), " ", retract, " ", dispose),
    a.itinerary ? stops : el("div", { class: "note" }, "itinerary not reported by this host"));
}

function hostName(address) { const i = address.lastIndexOf("/"); return i >= 0 ? address.slice(i + 1) : address; }
function mark(outcome) { return outcome === "DONE" ? "✓" : outcome === "FAILED" ? "✗" : outcome === "UNREACHABLE" ? "⊘" : outcome === "INTERRUPTED" ? "↯" : ""; }

// ---- events ----

function addEvent(e) {
  const list = document.getElementById("events");
  document.getElementById("no-events")?.remove();
  const time = new Date(e.t * 1000).toLocaleTimeString();
  const li = e.kind === "agent"
    ? el("li", { class: e.what, "data-agent": e.agent, "data-what": e.what }, el("span", { class: "t" }, time), el("span", { class: "what" }, e.what),
        simpleName(e.agentClass) + " " + shortId(e.agent) + " at " + hostName(e.host) + (e.detail ? ": " + e.detail : ""))
    : el("li", { class: "topic" }, el("span", { class: "t" }, time), el("span", { class: "what" }, e.topic), e.detail);
  list.prepend(li);
  while (list.children.length > MAX_EVENTS_SHOWN) list.lastChild.remove();
}

setInterval(() => { if (!model.connected) { drawnHosts = ""; renderAll(); } }, 1000);
connect();
