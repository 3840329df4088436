// The page's words and controls (web/app.js does the drawing): the status line, the caption under each panel
// (what the method is, what to look for), the controls (each shown only in the view where it acts, each slider
// with its value) and the heat map's legend. assemble_page.cmake puts this file in front of app.js.
"use strict";

const $ = (id) => document.getElementById(id);

// The status line: always says what the page is doing (state: loading, ready, fallback, error). The state is
// also body[data-status], which tests/web reads.
function setStatus(state, text) {
  document.body.dataset.status = state;
  $("status").textContent = text;
}
// An error before main() runs (bad data, a syntax error) must not leave "Loading" on the screen.
window.addEventListener("error", (e) => setStatus("error", "The page failed: " + e.message));

// Each panel's caption: the method's name and its caption from CGA_DATA.methods (the runtime's table, which
// also gives which methods, in what order, their colours), then what the method does and what to look for,
// by the method's name; a method with no notes here gets its table caption only.
const METHOD_NOTES = {
  "lbs": ["each bone's matrix moves the vertex and the moved points are averaged (the games-industry default)",
          "the twist strip pinches to a point at 180\u00b0 (the candy wrapper); elbows and shoulders thin out"],
  "dqs": ["the bones' dual quaternions (rotation + translation) are blended, then applied once",
          "the twist strip keeps its radius; a bone's scale is dropped"],
  "cga-points": ["each bone's CGA motor moves the vertex and the points are averaged: lbs computed with motors",
                 "the same picture as lbs (with lbs as the heat map's reference its panel is blue: rounding only)"],
  "cga-motors": ["the bones' motors (rotation + translation + uniform scale in one versor) are blended, then applied once",
                 "no candy wrapper, like dqs, and scaled bones keep their scale"],
  "cga-log": ["the bones' motor logarithms are blended, and the sum's closed-form exponential moves the vertex once",
              "no candy wrapper: the blend is a screw about its own axis; scales blend geometrically"],
};

function labelPanels() {
  const stage = $("stage"), captions = $("captions");
  const count = CGA_DATA.methods.length;
  CGA_DATA.methods.forEach(({name: m}, i) => {
    const d = document.createElement("div");
    d.className = "panel-label";
    d.style.left = (100 * i / count + 1) + "%";
    d.textContent = m;
    stage.appendChild(d);
    const c = document.createElement("div");
    c.className = "caption";
    c.append(Object.assign(document.createElement("b"), {textContent: m + ": " + CGA_DATA.methods[i].caption + ". "}));
    const notes = METHOD_NOTES[m];
    if (notes)
      c.append(notes[0] + ". ", Object.assign(document.createElement("i"), {textContent: "Look for: " + notes[1] + "."}));
    captions.appendChild(c);
  });
}

// What each panel's heat map compares, per panel [its own method, the reference]: one reference for every
// panel, so a panel's colours tell how far its own method moves a vertex from where the reference puts it.
function heatPairs(heat) {
  return CGA_DATA.methods.map((_, m) => [m, heat.ref]);
}

// The heat map's legend in plain words, with the colour bar; each panel's name says what it is compared
// with (and its label carries the pair as data-heat-a / data-heat-b, which tests/web reads).
function heatLegend(heat, scene) {
  const legend = $("legend"), names = CGA_DATA.methods.map((m) => m.name), ref = names[heat.ref];
  const pairs = heatPairs(heat);
  document.querySelectorAll(".panel-label").forEach((label, i) => {
    const [a, b] = pairs[i];
    label.textContent = names[i] + (!heat.on ? "" : a === b ? " (the reference)" : " vs " + names[b]);
    if (heat.on) {
      label.dataset.heatA = names[a];
      label.dataset.heatB = names[b];
    } else {
      delete label.dataset.heatA;
      delete label.dataset.heatB;
    }
  });
  legend.classList.toggle("hidden", !heat.on);
  $("heat-of").textContent = "of " + (scene === "twist" ? "the strip's length" : "the character's size");
  if (!heat.on) return;
  const of = scene === "twist" ? "the strip's length" : "the character's size (its bounding box's diagonal)";
  const red = +(100 * heat.scale).toPrecision(2) + "%";
  legend.replaceChildren(
      "Heat map: each panel colours a vertex by how far its own method puts it from where " + ref +
      " (the reference) puts it. blue: the same place",
      Object.assign(document.createElement("span"), {className: "bar"}),
      "red: " + red + " of " + of + " apart or more (green: half that). The " + ref + " panel is all blue: it " +
      "is the reference.");
}

// Where the canvas and the legend are and the window's size (CSS pixels; the legend's is empty while it is
// hidden), as body[data-canvas], body[data-legend] and body[data-window], for tests/web.
function noteLayout() {
  const box = (el) => {
    const r = el.getBoundingClientRect();
    return [r.left, r.top, r.width, r.height].map((v) => v.toFixed(0)).join(" ");
  };
  document.body.dataset.canvas = box($("view"));
  document.body.dataset.legend = $("legend").classList.contains("hidden") ? "" : box($("legend"));
  document.body.dataset.window = window.innerWidth + " " + window.innerHeight;
}

// Wires the controls to `state` and the renderer's palettes; returns update(), which re-reads them.
function setupControls(renderer, state) {
  $("model").textContent = CGA_DATA.model + ": " + CGA_DATA.fade + ".";
  const time = $("time"), weight = $("weight"), twistSlider = $("twist");
  time.max = CGA_DATA.times - 1;
  weight.max = CGA_DATA.weights - 1;
  twistSlider.max = CGA_DATA.twist.angles - 1;
  CGA_DATA.modes.forEach((m, i) => $("mode").add(new Option(m, i)));
  state.mode = CGA_DATA.modes.indexOf("screw");
  $("mode").value = state.mode;
  CGA_DATA.methods.forEach((m, i) => $("heat-ref").add(new Option(m.name, i)));
  $("heat-ref").value = state.heat.ref;
  state.twist = CGA_DATA.twist.angles - 1;
  twistSlider.value = state.twist;
  const update = () => {
    state.time = +time.value, state.weight = +weight.value, state.twist = +twistSlider.value;
    state.mode = +$("mode").value, state.scene = $("scene").value;
    state.heat = {on: $("heat").checked, ref: +$("heat-ref").value, scale: +$("heat-scale").value};
    const labels = CGA_DATA.timeLabels;
    $("time-value").textContent = (state.time + 1) + "/" + CGA_DATA.times + (labels ? " (" + labels[state.time] + ")" : "");
    $("weight-value").textContent = (state.weight / (CGA_DATA.weights - 1)).toFixed(2) + " of clip b";
    $("twist-value").textContent = Math.round(180 * state.twist / (CGA_DATA.twist.angles - 1)) + "\u00b0";
    // Each control only where it acts: time, fade, mode and play move the character; twist turns the strip.
    for (const el of document.querySelectorAll("[data-for]")) {
      const f = el.dataset.for;
      el.classList.toggle("hidden", f === "heat" ? !state.heat.on : f !== state.scene);
    }
    heatLegend(state.heat, state.scene);
    noteLayout();
    dirty = true;
    renderer.setPalette("character", characterPalette(state.mode, state.time, state.weight));
    renderer.setPalette("twist", twistPalette(state.twist));
  };
  for (const id of ["time", "weight", "twist", "mode", "scene", "heat", "heat-ref", "heat-scale"])
    $(id).addEventListener("input", update);
  $("play").onclick = () => {
    state.playing = !state.playing;
    $("play").textContent = state.playing ? "pause" : "play";
  };
  // Orbit: drag turns, the wheel zooms; one camera for all panels.
  const canvas = $("view");
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointerup", () => { drag = null; });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    camera.yaw -= 0.01 * (e.clientX - drag[0]);
    camera.pitch = Math.max(-1.4, Math.min(1.4, camera.pitch + 0.01 * (e.clientY - drag[1])));
    drag = [e.clientX, e.clientY];
    dirty = true;
  });
  canvas.addEventListener("wheel", (e) => { e.preventDefault(); camera.zoom *= Math.exp(0.001 * e.deltaY); dirty = true; }, {passive: false});
  update();
  return update;
}
