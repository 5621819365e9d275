// rtedge-web's page: the daemon's state from /api/events (server-sent
// events), the overlay from /stream.mjpg, and controls built from the
// daemon's param_state_t that POST to /api/params. Plain script, no build.
"use strict";

const LAYERS = ["roi", "edges", "segments", "lanes", "contours", "grasp", "labels"];
const $ = (id) => document.getElementById(id);
let state = null;            // the last snapshot
let pending = null;          // {id, what} of the request sent last
let built = "";              // the key list the controls were built for
let dragging = null;         // the ROI vertex being dragged
let roiDraft = null;         // vertices while dragging, [[x, y], ...]
let roiDrawn = null;         // what the ROI's SVG shows, rebuilt only on change

function token() { return $("token").value || sessionStorage.getItem("rtedge-token") || ""; }

async function post(path, body) {
  const r = await fetch(path, {
    method: "POST",
    headers: { "Content-Type": "application/json", "X-RTEdge-Token": token() },
    body: JSON.stringify(body),
  });
  let j = null;
  try { j = await r.json(); } catch (e) { j = { ok: false, reason: "HTTP " + r.status }; }
  return j;
}

function showOutcome(cls, text) {
  const o = $("outcome");
  o.className = "outcome " + cls;
  o.textContent = text;
}

async function send(values, what) {
  showOutcome("pending", "Sending " + what + "…");
  const j = await post("/api/params", { values });
  if (!j.ok) { pending = null; showOutcome("refused", "Refused: " + j.reason); return; }
  pending = { id: j.request_id, what };
  showOutcome("pending", "Request " + j.request_id + " (" + what + ") sent…");
}

// ---- controls built from the schema ----

function controlId(name) { return "p-" + name.replace(/\./g, "-"); }

function describe(k) {
  let r = k.help.split("\n")[0];
  if (k.type === "int" || k.type === "real") r += " (" + k.min + ".." + k.max +
    (k.unset !== null ? ", or " + k.unset + " for the default" : "") + ")";
  return r;
}

function buildControls(params) {
  const box = $("controls");
  box.textContent = "";
  for (const k of params.keys) {
    const row = document.createElement("div");
    row.className = "control";
    row.title = k.help;
    const label = document.createElement("label");
    label.className = "name";
    label.htmlFor = controlId(k.name);
    label.innerHTML = "";
    label.append(k.name);
    if (k.unit) { const u = document.createElement("span"); u.className = "unit"; u.textContent = " " + k.unit; label.append(u); }
    const inputs = document.createElement("div");
    inputs.className = "inputs";
    let input;
    if (k.type === "bool") {
      input = document.createElement("input");
      input.type = "checkbox";
      input.addEventListener("change", () => send({ [k.name]: input.checked }, k.name));
    } else if (k.type === "choice") {
      input = document.createElement("select");
      for (const c of k.choices) { const o = document.createElement("option"); o.value = o.textContent = c; input.append(o); }
      input.addEventListener("change", () => send({ [k.name]: input.value }, k.name));
    } else if (k.type === "text") {
      input = document.createElement("input");
      input.type = "text";
      input.maxLength = 255;
      input.addEventListener("change", () => send({ [k.name]: input.value }, k.name));
    } else {
      // numbers: a slider where the range is one a hand can cover, and the exact value
      input = document.createElement("input");
      input.type = "number";
      input.step = k.type === "int" ? "1" : "any";
      const lo = k.unset !== null ? Math.min(k.min, k.unset) : k.min;
      if (k.max - lo <= 100000) {
        const slider = document.createElement("input");
        slider.type = "range";
        slider.id = controlId(k.name) + "-slider";
        slider.min = lo; slider.max = k.max;
        slider.step = k.type === "int" ? 1 : (k.max - lo) / 1000;
        slider.addEventListener("input", () => { input.value = slider.value; });
        slider.addEventListener("change", () => send({ [k.name]: Number(slider.value) }, k.name));
        inputs.append(slider);
      }
      input.addEventListener("change", () => {
        if (input.value.trim() === "") return;
        send({ [k.name]: Number(input.value) }, k.name);
      });
    }
    input.id = controlId(k.name);
    input.dataset.name = k.name;
    inputs.prepend(input);
    row.append(label, inputs);
    const d = document.createElement("div");
    d.className = "unit";
    d.style.gridColumn = "1 / -1";
    d.textContent = describe(k);
    row.append(d);
    box.append(row);
  }
}

function setValue(k) {
  const input = $(controlId(k.name));
  if (!input || document.activeElement === input) return;
  if (k.type === "bool") input.checked = k.value;
  else input.value = k.value;
  const slider = $(controlId(k.name) + "-slider");
  if (slider && document.activeElement !== slider) slider.value = k.value;
  input.disabled = !k.settable;
  if (slider) slider.disabled = !k.settable;
  input.closest(".control").classList.toggle("locked", !k.settable);
}

function keyOf(name) { return state && state.params ? state.params.keys.find((k) => k.name === name) : null; }

// ---- layers and the ROI ----

function buildLayers() {
  const box = $("layers");
  for (const name of LAYERS) {
    const label = document.createElement("label");
    const cb = document.createElement("input");
    cb.type = "checkbox";
    cb.id = "layer-" + name;
    cb.addEventListener("change", () => {
      const on = LAYERS.filter((n) => $("layer-" + n).checked);
      send({ "debug.layers": on.join(",") }, "debug.layers");
    });
    label.append(cb, " " + name);
    box.append(label);
  }
}

function showLayers() {
  const k = keyOf("debug.layers");
  if (!k) return;
  const on = k.value.split(",").map((s) => s.trim());
  for (const name of LAYERS) {
    const cb = $("layer-" + name);
    cb.checked = on.includes("all") || on.includes(name);
    cb.disabled = !k.settable;
  }
}

function roiVertices() {
  if (roiDraft) return roiDraft;
  const k = keyOf("lane.roi");
  if (!k) return [];
  return k.value.split(";").map((p) => p.split(",").map(Number)).filter((p) => p.length === 2);
}

function drawRoi() {
  const svg = $("roi");
  const v = roiVertices();
  const k = keyOf("lane.roi");
  // Rebuilding on every update would replace the vertex under a pointer
  // that is about to press it.
  const shown = JSON.stringify(v) + (k && k.settable ? " settable" : "");
  if (shown === roiDrawn) return;
  roiDrawn = shown;
  svg.textContent = "";
  if (!v.length) return;
  const ns = "http://www.w3.org/2000/svg";
  const poly = document.createElementNS(ns, "polygon");
  poly.setAttribute("points", v.map((p) => p.join(",")).join(" "));
  svg.append(poly);
  v.forEach((p, i) => {
    const c = document.createElementNS(ns, "circle");
    c.setAttribute("cx", p[0]); c.setAttribute("cy", p[1]); c.setAttribute("r", 0.012);
    c.dataset.index = i;
    c.classList.add("roi-vertex");
    if (k && k.settable) c.addEventListener("pointerdown", (e) => {
      dragging = i; roiDraft = roiVertices().map((q) => q.slice());
      svg.setPointerCapture(e.pointerId);
    });
    svg.append(c);
  });
}

function setupRoiDrag() {
  const svg = $("roi");
  svg.addEventListener("pointermove", (e) => {
    if (dragging === null) return;
    const r = svg.getBoundingClientRect();
    const x = Math.min(1, Math.max(0, (e.clientX - r.left) / r.width));
    const y = Math.min(1, Math.max(0, (e.clientY - r.top) / r.height));
    roiDraft[dragging] = [Number(x.toFixed(3)), Number(y.toFixed(3))];
    drawRoi();
  });
  svg.addEventListener("pointerup", () => {
    if (dragging === null) return;
    dragging = null;
    const text = roiDraft.map((p) => p[0] + "," + p[1]).join(";");
    roiDraft = null;
    send({ "lane.roi": text }, "lane.roi");
  });
}

// ---- the state as it comes ----

function fmt(v, digits) { return v === null || v === undefined ? "–" : Number(v).toFixed(digits); }

function showStatus(s) {
  if (!s) return;
  $("source").textContent = s.source;
  $("st-state").textContent = s.state;
  $("st-fps").textContent = fmt(s.fps, 1);
  $("st-latency").textContent = (s.p50_us / 1000).toFixed(2) + " / " + (s.p99_us / 1000).toFixed(2) + " ms";
  $("st-misses").textContent = s.deadline_misses;
  $("st-dropped").textContent = s.dropped + " / " + s.skipped;
  $("st-processed").textContent = s.processed;
  const box = $("stages");
  box.textContent = "";
  const max = Math.max(1, ...s.stages.map((t) => t.mean_us));
  for (const t of s.stages) {
    const row = document.createElement("div");
    row.className = "bar";
    const name = document.createElement("span"); name.textContent = t.name;
    const track = document.createElement("div");
    const fill = document.createElement("div"); fill.className = "fill";
    fill.style.width = (100 * t.mean_us / max).toFixed(1) + "%";
    track.append(fill);
    const num = document.createElement("span"); num.className = "num"; num.textContent = t.mean_us;
    row.append(name, track, num);
    box.append(row);
  }
}

function side(l) {
  if (!l.found) return "not found";
  return (l.predicted ? "predicted" : "seen") + ", confidence " + l.confidence.toFixed(2);
}

function showLanes(l) {
  if (!l) return;
  $("lane-offset").textContent = l.centre_valid ? l.offset_px.toFixed(1) + " px" : "–";
  $("lane-heading").textContent = l.centre_valid ? l.heading_deg.toFixed(1) + "°" : "–";
  $("lane-left").textContent = side(l.left);
  $("lane-right").textContent = side(l.right);
}

function showGrasp(g) {
  const body = $("objects").tBodies[0];
  body.textContent = "";
  if (!g) return;
  g.objects.forEach((o, i) => {
    const tr = document.createElement("tr");
    for (const v of [i, o.shape, o.x.toFixed(1), o.y.toFixed(1), o.angle_deg.toFixed(1) + "°",
                     o.opening_px.toFixed(1), o.area.toFixed(0), o.score.toFixed(2)]) {
      const td = document.createElement("td"); td.textContent = v; tr.append(td);
    }
    body.append(tr);
  });
}

function showParams(p) {
  if (!p) return;
  const names = p.keys.map((k) => k.name + ":" + k.type).join(" ");
  if (names !== built) { buildControls(p); built = names; }
  for (const k of p.keys) setValue(k);
  $("params-off").hidden = p.enabled;
  $("save").disabled = !p.enabled;
  showLayers();
  if (dragging === null) drawRoi();
  if (pending && p.request_id === pending.id) {
    if (p.outcome === "applied") showOutcome("applied", "Request " + p.request_id + " applied (" + pending.what + ").");
    else if (p.outcome === "refused") showOutcome("refused", "Request " + p.request_id + " refused: " + p.reason);
    else if (p.outcome === "saved") {
      showOutcome("saved", "Saved: " + p.reason + ".");
      $("download").hidden = false;
    }
    pending = null;
  }
}

function show(snap) {
  state = snap;
  showStatus(snap.status);
  showLanes(snap.lanes);
  showGrasp(snap.grasp);
  showParams(snap.params);
  $("no-overlay").hidden = snap.overlay.frames > 0;
  $("overlay").dataset.frames = snap.overlay.frames;
}

function connect() {
  const es = new EventSource("/api/events");
  es.onopen = () => { $("link").textContent = "live"; $("link").classList.add("live"); };
  es.onmessage = (e) => show(JSON.parse(e.data));
  es.onerror = () => { $("link").textContent = "reconnecting"; $("link").classList.remove("live"); };
}

function init() {
  const m = location.hash.match(/token=([^&]+)/);
  if (m) sessionStorage.setItem("rtedge-token", decodeURIComponent(m[1]));
  $("token").value = sessionStorage.getItem("rtedge-token") || "";
  $("token").addEventListener("change", () => sessionStorage.setItem("rtedge-token", $("token").value));
  buildLayers();
  setupRoiDrag();
  $("save").addEventListener("click", async () => {
    showOutcome("pending", "Saving…");
    const j = await post("/api/save", {});
    if (!j.ok) { showOutcome("refused", "Refused: " + j.reason); return; }
    pending = { id: j.request_id, what: "save" };
  });
  connect();
}

init();
