// sva ground view: draws the server's picture (GET /ws, {"type": "state", ...}) with plain
// SVG and DOM. Every text from the traffic goes in through textContent, never as markup.
"use strict";

const SVGNS = "http://www.w3.org/2000/svg";
const EARTH_R = 6371008.8; // mean Earth radius, metres (local equirectangular frame)
const UAV_COLOURS = ["#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4", "#42d4f4",
                     "#f032e6", "#9a6324", "#469990", "#800000", "#808000", "#000075"];
let state = null;
let view = null; // the map's cell -> pixel mapping

function $(id) { return document.getElementById(id); }

function el(name, attrs, parent, text) {
  const e = document.createElementNS(SVGNS, name);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  if (parent) parent.appendChild(e);
  return e;
}

function setText(id, v) { $(id).textContent = (v === null || v === undefined) ? "–" : String(v); }

function clear(node) { while (node.firstChild) node.removeChild(node.firstChild); }

function colour(uavId) { return UAV_COLOURS[Math.abs(uavId) % UAV_COLOURS.length]; }

function us(v) { return (v === null || v === undefined) ? "–" : (v / 1000).toFixed(3) + " ms"; }

// --- frame ----------------------------------------------------------------------------

function cellToGeo(frame, x, y) {
  const north = y * frame.cell_m, east = x * frame.cell_m;
  const lat = frame.lat + (north / EARTH_R) * 180 / Math.PI;
  const lon = frame.lon + (east / (EARTH_R * Math.cos(frame.lat * Math.PI / 180))) * 180 / Math.PI;
  return [lat, lon];
}

function tickTime(frame, t) {
  const t0 = Date.parse(frame.t0);
  if (Number.isNaN(t0)) return "";
  return new Date(t0 + t * frame.tick_s * 1000).toISOString().replace(".000Z", "Z");
}

function niceLength(max) { // 1, 2 or 5 times a power of ten, at most max
  const p = Math.pow(10, Math.floor(Math.log10(max)));
  for (const m of [5, 2, 1]) if (m * p <= max) return m * p;
  return p;
}

// --- map ------------------------------------------------------------------------------

function drawMap(s) {
  const svg = $("map");
  clear(svg);
  const W = +svg.getAttribute("width"), H = +svg.getAttribute("height"), pad = 24;
  const pts = [];
  if (s.mission && s.mission.depot) pts.push(s.mission.depot);
  for (const t of s.targets) pts.push([t.x, t.y]);
  for (const u of s.uavs) { pts.push([u.x, u.y]); for (const p of u.track) pts.push([p[1], p[2]]); }
  if (!pts.length) { el("text", {x: W / 2, y: H / 2, "text-anchor": "middle", class: "label"}, svg, "no mission yet"); view = null; return; }
  let minx = Math.min(...pts.map(p => p[0])), maxx = Math.max(...pts.map(p => p[0]));
  let miny = Math.min(...pts.map(p => p[1])), maxy = Math.max(...pts.map(p => p[1]));
  minx -= 1; maxx += 1; miny -= 1; maxy += 1;
  const k = Math.min((W - 2 * pad) / (maxx - minx), (H - 2 * pad) / (maxy - miny));
  view = {k, minx, miny, pad, H};
  const sx = x => pad + (x - minx) * k, sy = y => H - pad - (y - miny) * k;
  view.sx = sx; view.sy = sy;
  const byId = new Map(s.targets.map(t => [t.id, t]));
  const uavById = new Map(s.uavs.map(u => [u.id, u]));
  const depot = s.mission && s.mission.depot;
  // routes of the plan in force: from the UAV through its targets, home
  if (s.plan) {
    for (const r of s.plan.routes) {
      const u = uavById.get(r.uav);
      if (!u || u.lost || !r.targets.length) continue;
      const line = [[u.x, u.y]];
      for (const id of r.targets) { const t = byId.get(id); if (t) line.push([t.x, t.y]); }
      if (depot) line.push(depot);
      el("polyline", {class: "route", "data-uav": r.uav, stroke: colour(r.uav),
                      points: line.map(p => sx(p[0]) + "," + sy(p[1])).join(" ")}, svg);
    }
  }
  for (const u of s.uavs) {
    if (u.track.length > 1) {
      el("polyline", {class: "track", "data-uav": u.id,
                      points: u.track.map(p => sx(p[1]) + "," + sy(p[2])).join(" ")}, svg);
    }
  }
  if (depot) {
    el("rect", {class: "depot", x: sx(depot[0]) - 6, y: sy(depot[1]) - 6, width: 12, height: 12}, svg);
    el("text", {class: "label", x: sx(depot[0]) + 8, y: sy(depot[1]) + 12}, svg, "depot");
  }
  for (const t of s.targets) {
    const c = el("circle", {class: "target state-" + t.state, "data-id": t.id, "data-state": t.state,
                            cx: sx(t.x), cy: sy(t.y), r: Math.max(4, Math.min(9, k * 0.35))}, svg);
    el("title", {}, c, `target ${t.id}: ${t.state.replace("_", " ")}, window [${t.start}, ${t.end}), need ${t.need}`);
    el("text", {class: "label", x: sx(t.x) + 7, y: sy(t.y) - 6}, svg, "T" + t.id);
  }
  for (const u of s.uavs) {
    const x = sx(u.x), y = sy(u.y);
    const g = el("g", {class: "uav-group"}, svg);
    const p = el("polygon", {class: "uav" + (u.lost ? " lost" : ""), "data-id": u.id,
                             "data-lost": u.lost ? "true" : "false", fill: u.lost ? "#fff" : colour(u.id),
                             points: `${x},${y - 8} ${x - 7},${y + 6} ${x + 7},${y + 6}`}, g);
    el("title", {}, p, `UAV ${u.id}${u.lost ? " (lost)" : ""}: (${u.x}, ${u.y}), fuel ${u.fuel}`);
    el("text", {class: "label", x: x + 8, y: y + 4}, g, "U" + u.id + (u.lost ? " lost" : ""));
    if (u.lost) {
      el("line", {x1: x - 8, y1: y - 8, x2: x + 8, y2: y + 8, stroke: "#c00", "stroke-width": 2}, g);
      el("line", {x1: x - 8, y1: y + 8, x2: x + 8, y2: y - 8, stroke: "#c00", "stroke-width": 2}, g);
    }
  }
  drawScale(s);
}

function drawScale(s) {
  const svg = $("scale");
  clear(svg);
  if (!view) return;
  const unit = s.frame ? s.frame.cell_m : 1; // metres (frame) or cells per cell
  const maxPx = 180;
  const len = niceLength(maxPx / view.k * unit);
  const px = len / unit * view.k;
  el("line", {x1: 5, y1: 16, x2: 5 + px, y2: 16, stroke: "#223", "stroke-width": 3}, svg);
  el("line", {x1: 5, y1: 10, x2: 5, y2: 20, stroke: "#223"}, svg);
  el("line", {x1: 5 + px, y1: 10, x2: 5 + px, y2: 20, stroke: "#223"}, svg);
  const text = s.frame ? (len >= 1000 ? (len / 1000) + " km" : len + " m") : len + (len === 1 ? " cell" : " cells");
  el("text", {id: "scale-text", class: "label", x: 10 + px, y: 20}, svg, text);
}

function onCursor(ev) {
  if (!view || !state) return;
  const r = $("map").getBoundingClientRect();
  const x = view.minx + (ev.clientX - r.left - view.pad) / view.k;
  const y = view.miny + (view.H - view.pad - (ev.clientY - r.top)) / view.k;
  let text = `cell (${Math.round(x)}, ${Math.round(y)})`;
  if (state.frame) {
    const [lat, lon] = cellToGeo(state.frame, x, y);
    text += `  ${lat.toFixed(6)}°, ${lon.toFixed(6)}°  ${(x * state.frame.cell_m).toFixed(0)} m E, ${(y * state.frame.cell_m).toFixed(0)} m N`;
  }
  $("cursor").textContent = text;
}

// --- Gantt ----------------------------------------------------------------------------

function drawGantt(s) {
  const svg = $("gantt");
  clear(svg);
  const rowH = 16, left = 60, top = 22;
  const W = +svg.getAttribute("width");
  svg.setAttribute("height", String(top + rowH * Math.max(1, s.targets.length) + 24));
  const tmax = Math.max(10, s.now, s.end || 0, ...s.targets.map(t => t.end)) + 1;
  const sx = t => left + (t / tmax) * (W - left - 10);
  const bottom = top + rowH * s.targets.length;
  for (let t = 0, step = niceLength(tmax / 8); t <= tmax; t += step) {
    el("line", {x1: sx(t), y1: top - 4, x2: sx(t), y2: bottom, stroke: "#e2e5e9"}, svg);
    el("text", {class: "label", x: sx(t), y: bottom + 14, "text-anchor": "middle"}, svg, String(t));
  }
  s.targets.forEach((t, i) => {
    const y = top + i * rowH;
    el("text", {class: "label", x: 4, y: y + 11}, svg, "T" + t.id + " ×" + t.need);
    const w = el("rect", {class: "window state-" + t.state, "data-id": t.id, x: sx(t.start), y: y + 2,
                          width: Math.max(1, sx(t.end) - sx(t.start)), height: rowH - 4}, svg);
    el("title", {}, w, `target ${t.id} window [${t.start}, ${t.end}): ${t.state.replace("_", " ")}`);
    for (const v of t.visits || []) {
      const end = v[2] === null ? s.now : v[2];
      const r = el("rect", {class: "visit", x: sx(v[1]), y: y + 6, width: Math.max(1, sx(end) - sx(v[1])), height: 4}, svg);
      el("title", {}, r, `UAV ${v[0]} at target ${t.id} from ${v[1]} to ${v[2] === null ? "now" : v[2]}`);
    }
    if (t.planned && t.planned.length && !(t.visits || []).length) {
      el("text", {class: "label", x: sx(t.end) + 4, y: y + 11}, svg, "U" + t.planned.join(",U"));
    }
  });
  for (const r of s.replans) {
    const m = el("line", {class: "replan-mark" + (r.accepted ? "" : " refused"), x1: sx(r.now), y1: 2,
                          x2: sx(r.now), y2: top - 6}, svg);
    el("title", {}, m, `replan at tick ${r.now} (${r.event})` + (r.accepted ? `: cost ${r.cost}, covers ${r.covered}` : ": refused"));
  }
  el("text", {class: "label", x: 4, y: 12}, svg, "replans");
  el("line", {class: "now-line", x1: sx(s.now), y1: top - 4, x2: sx(s.now), y2: bottom}, svg);
}

// --- tables and lists -----------------------------------------------------------------

function drawPanels(s) {
  setText("source", s.source);
  setText("now", s.now);
  $("clock").textContent = s.frame ? tickTime(s.frame, s.now) : "";
  $("map-unit").textContent = s.frame ? `(cells of ${s.frame.cell_m} m; north up)` : "(cells)";
  setText("uav-count", s.uavs.length);
  setText("uav-lost-count", s.uavs.filter(u => u.lost).length);
  setText("warning-count", s.warnings.count);
  const p = s.plan;
  setText("plan-id", p ? p.plan_id : null);
  setText("plan-algorithm", p ? p.algorithm : null);
  setText("plan-status", p ? p.status : null);
  setText("plan-covered", p ? p.covered : null);
  setText("plan-cost", p ? p.cost : null);
  $("plan-solve").textContent = p ? us(p.solve_us) : "–";
  const n = s.node, st = n.status;
  setText("replan-count", n.replans_answered);
  setText("refused-count", n.refused);
  $("node-solve").textContent = us(n.last_solve_us);
  if (st) {
    setText("node-state", st.state);
    setText("node-algorithm", st.algorithm);
    setText("node-plan-id", st.last_plan_id);
    setText("node-revisions", `${st.fleet_revision} / ${st.mission_revision}`);
    setText("node-plans", st.plans_published);
    const parts = Object.entries(st.rejected).filter(([, v]) => v > 0).map(([k, v]) => `${k} ${v}`);
    $("node-rejected").textContent = st.rejected_total + (parts.length ? ` (${parts.join(", ")})` : "");
    $("node-age").textContent = "seq " + st.seq;
  }
  const log = $("event-log");
  clear(log);
  for (const e of s.log.slice().reverse()) {
    const li = document.createElement("li");
    li.className = e.kind;
    li.textContent = `t=${e.t} [${e.kind}] ${e.text}`;
    log.appendChild(li);
  }
  const w = $("warnings");
  clear(w);
  for (const e of s.warnings.recent.slice().reverse()) {
    const li = document.createElement("li");
    li.textContent = `${e.channel}: ${e.text}`;
    w.appendChild(li);
  }
}

let drawnKey = null; // what the map and the Gantt were last drawn from

function draw(s) {
  state = s;
  const key = JSON.stringify([s.uavs, s.targets, s.plan, s.replans, s.now, s.end, s.frame, s.mission]);
  const parts = [["panels", drawPanels]];
  if (key !== drawnKey) parts.push(["map", drawMap], ["gantt", drawGantt]);
  drawnKey = key;
  for (const [name, f] of parts) {
    try { f(s); } catch (err) { console.error("ground view: drawing the " + name + ":", err); }
  }
  document.body.dataset.version = String(s.version);
}

function connect() {
  // The page's own ?token= (docs/ground.md "Trust"), passed on to the websocket.
  const token = new URLSearchParams(location.search).get("token");
  const ws = new WebSocket((location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws" +
                           (token ? "?token=" + encodeURIComponent(token) : ""));
  ws.onopen = () => { $("conn").textContent = "up"; $("conn").className = "up"; };
  ws.onclose = () => {
    $("conn").textContent = "down, reconnecting"; $("conn").className = "down";
    setTimeout(connect, 1000);
  };
  ws.onmessage = ev => {
    let msg;
    try { msg = JSON.parse(ev.data); } catch (err) { console.error("ground view: bad update", err); return; }
    if (msg.type === "state") draw(msg);
  };
}

$("map").addEventListener("mousemove", onCursor);
connect();
