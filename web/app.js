// The page's program (after web/ui.js, which holds the words and controls): decodes CGA_DATA (written by
// cga-demo --web), starts WebGPU when navigator.gpu gives an adapter and its first frame comes back in time,
// else WebGL 2, draws every method of CGA_DATA.methods (the runtime's method table, in its order) in a panel
// of its own with one orbit camera, and keeps the status line told.
// Opened as index.html#selftest it skins a fixed frame with every method, reads the vertices back,
// compares them with the CPU jobs' vertices in CGA_DATA and writes "PATH ok|fail MAXDEV" into #cga-result
// (also the first line of the promise window.cgagenResult, which tests/targets/browser_run.py waits for).
// Options in the fragment, joined by "&": selftest, webgl2 (force the WebGL 2 path), heat (heat map on),
// twist (the twist strip view), paused (the animation starts paused), frames (the result comes after 5
// frames of the animation loop, playing: tests/web's check of the interactive path), mismatch (the self-test
// compares each method with the next one's CPU vertices: it must fail; tests/web checks that the comparison
// can). No libraries: a few matrices are all the page needs.
"use strict";

// The methods come from the data, never from this file: CGA_DATA.methods is the runtime's method table (name,
// colour, vec4s per prepared entry), and a method's index is its code in the shaders, whose skin() is
// generated from the same table. One pose's palette holds every method's prepared palette in this order.
const METHODS = CGA_DATA.methods;
const ENTRY_FLOATS = METHODS.reduce((n, m) => n + 4 * m.vec4s, 0);  // one entry, every method
const TOLERANCE = 1e-4;  // of the character's size: the bound every GPU path is held to

function decodeFloats(b64) {
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}
function decodeUints(b64) { return new Uint32Array(decodeFloats(b64).buffer); }

// ---- the scenes: rest mesh, palettes, framing
function makeScene(src, poses) {
  const vertices = decodeFloats(src.vertices);
  const floatsPerPalette = src.entries * ENTRY_FLOATS;
  const palettes = decodeFloats(src.palettes);
  if (palettes.length !== poses * floatsPerPalette)
    throw new Error("the data's palettes (" + palettes.length + " floats) are not " + poses + " poses of " +
                    src.entries + " entries x " + ENTRY_FLOATS + " floats (the methods' prepared entries)");
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let v = 0; v < src.vertexCount; ++v)
    for (let k = 0; k < 3; ++k) {
      const x = vertices[CGA_DATA.vertexFloats * v + k];
      lo[k] = Math.min(lo[k], x), hi[k] = Math.max(hi[k], x);
    }
  const extent = [0, 1, 2].map((k) => hi[k] - lo[k]);
  const up = extent.indexOf(Math.max(...extent));  // a character stands along its longest side
  return {
    vertexCount: src.vertexCount, entries: src.entries, vertices, indices: decodeUints(src.indices),
    palettes, floatsPerPalette,
    center: [0, 1, 2].map((k) => 0.5 * (lo[k] + hi[k])), radius: 0.5 * Math.hypot(...extent), up,
  };
}

const character = makeScene(CGA_DATA.character, CGA_DATA.modes.length * CGA_DATA.times * CGA_DATA.weights);
const twist = makeScene(CGA_DATA.twist, CGA_DATA.twist.angles);
// Where the character is in each pose (bounding box centre, same order as the palettes): the camera follows.
const characterCenters = decodeFloats(CGA_DATA.character.centers);

// The palette of the character at (mode, time step, weight step), or of the strip at angle step a.
function characterPalette(mode, t, w) {
  const n = character.floatsPerPalette;
  const i = (mode * CGA_DATA.times + t) * CGA_DATA.weights + w;
  character.center = Array.from(characterCenters.subarray(3 * i, 3 * i + 3));
  return character.palettes.subarray(i * n, (i + 1) * n);
}
function twistPalette(a) {
  const n = twist.floatsPerPalette;
  return twist.palettes.subarray(a * n, (a + 1) * n);
}

// ---- camera: orbit around the scene's centre; column-major 4x4 matrices
function mul4(a, b) {
  const o = new Float32Array(16);
  for (let c = 0; c < 4; ++c)
    for (let r = 0; r < 4; ++r) {
      let s = 0;
      for (let k = 0; k < 4; ++k) s += a[k * 4 + r] * b[c * 4 + k];
      o[c * 4 + r] = s;
    }
  return o;
}
function normalize3(v) { const l = Math.hypot(...v); return v.map((x) => x / l); }
function cross3(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function dot3(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

const camera = {yaw: 0.6, pitch: 0.25, zoom: 1.0};
// WebGPU's clip depth is [0, 1], WebGL's [-1, 1]: zeroToOne picks the projection.
function viewProjection(scene, aspect, zeroToOne) {
  const upAxis = [0, 0, 0];
  upAxis[scene.up] = 1;
  const a = (scene.up + 1) % 3, b = (scene.up + 2) % 3;  // the ground plane's axes
  const dist = 3.0 * scene.radius * camera.zoom;
  const eye = scene.center.slice();
  eye[a] += dist * Math.cos(camera.pitch) * Math.sin(camera.yaw);
  eye[b] += dist * Math.cos(camera.pitch) * Math.cos(camera.yaw);
  eye[scene.up] += dist * Math.sin(camera.pitch);
  const f = normalize3(scene.center.map((c, k) => c - eye[k]));
  const s = normalize3(cross3(f, upAxis));
  const u = cross3(s, f);
  const view = new Float32Array([s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
                                 -dot3(s, eye), -dot3(u, eye), dot3(f, eye), 1]);
  const near = 0.05 * dist, far = 4 * dist, fy = 1 / Math.tan(0.5 * 0.75);
  const proj = new Float32Array(16);
  proj[0] = fy / aspect, proj[5] = fy, proj[11] = -1;
  if (zeroToOne) proj[10] = far / (near - far), proj[14] = near * far / (near - far);
  else proj[10] = (far + near) / (near - far), proj[14] = 2 * far * near / (near - far);
  return mul4(proj, view);
}

// ---- WebGL 2: one program (skin.vert.glsl with the generated blends and the table's skin()), the palette in
// an RGBA32F texture
async function createWebGL2(canvas) {
  const gl = canvas.getContext("webgl2", {antialias: true, preserveDrawingBuffer: true});
  if (!gl) throw new Error("no WebGL 2 context");
  function shader(type, text) {
    const s = gl.createShader(type);
    gl.shaderSource(s, "#version 300 es\n" + text);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error("GLSL ES: " + gl.getShaderInfoLog(s));
    return s;
  }
  const prog = gl.createProgram();
  gl.attachShader(prog, shader(gl.VERTEX_SHADER, $("glsl-vertex").textContent));
  gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, $("glsl-fragment").textContent));
  gl.transformFeedbackVaryings(prog, ["v_position"], gl.SEPARATE_ATTRIBS);
  gl.linkProgram(prog);
  if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error("link: " + gl.getProgramInfoLog(prog));
  const loc = {};
  for (const n of ["u_palette", "u_entries", "u_view_proj", "u_method", "u_heat", "u_heat_a", "u_heat_b", "u_heat_scale",
                   "u_color", "u_light"]) loc[n] = gl.getUniformLocation(prog, n);

  function upload(scene) {
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    const vbo = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, vbo);
    gl.bufferData(gl.ARRAY_BUFFER, scene.vertices, gl.STATIC_DRAW);
    const stride = 4 * CGA_DATA.vertexFloats;
    [["a_position", 3, 0], ["a_normal", 3, 3], ["a_joints", 4, 6], ["a_weights", 4, 10]].forEach(([name, n, off]) => {
      const l = gl.getAttribLocation(prog, name);
      if (l < 0) return;
      gl.enableVertexAttribArray(l);
      gl.vertexAttribPointer(l, n, gl.FLOAT, false, stride, 4 * off);
    });
    const ibo = gl.createBuffer();
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ibo);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, scene.indices, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    const texels = scene.floatsPerPalette / 4, rows = Math.ceil(texels / 1024);
    const tex = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, tex);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, 1024, rows);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    return {vao, tex, rows, staging: new Float32Array(1024 * rows * 4), scene};
  }
  const gpu = {character: upload(character), twist: upload(twist)};

  return {
    name: "webgl2",
    describe: () => {
      const ext = gl.getExtension("WEBGL_debug_renderer_info");
      return "WebGL 2: " + (ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER));
    },
    setPalette(which, floats) {
      const g = gpu[which];
      g.staging.set(floats);
      gl.bindTexture(gl.TEXTURE_2D, g.tex);
      gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, 1024, g.rows, gl.RGBA, gl.FLOAT, g.staging);
    },
    bind(which, method, heat) {
      gl.useProgram(prog);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, gpu[which].tex);
      gl.uniform1i(loc.u_palette, 0);
      gl.uniform1i(loc.u_entries, gpu[which].scene.entries);
      gl.uniform1i(loc.u_method, method);
      gl.uniform1i(loc.u_heat, heat.on ? 1 : 0);
      gl.uniform1i(loc.u_heat_a, heat.pairs[method][0]);
      gl.uniform1i(loc.u_heat_b, heat.pairs[method][1]);
      gl.uniform1f(loc.u_heat_scale, heat.scale);
      gl.uniform3fv(loc.u_color, METHODS[method].colour);
      gl.bindVertexArray(gpu[which].vao);
    },
    // Draws a panel per method; resolves when the GPU is done (the frame time includes the work).
    async draw(which, heat) {
      const scene = gpu[which].scene;
      gl.enable(gl.DEPTH_TEST);
      gl.enable(gl.SCISSOR_TEST);
      const pw = Math.floor(canvas.width / METHODS.length), h = canvas.height;
      const vp = viewProjection(scene, pw / h, false);
      const light = normalize3([0.3, 0.5, 0.8]);
      for (let m = 0; m < METHODS.length; ++m) {
        gl.viewport(m * pw, 0, pw, h);
        gl.scissor(m * pw, 0, pw, h);
        gl.clearColor(0.11 + 0.02 * (m % 2), 0.12, 0.14, 1);
        gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
        this.bind(which, m, heat);
        gl.uniformMatrix4fv(loc.u_view_proj, false, vp);
        gl.uniform3fv(loc.u_light, light);
        gl.drawElements(gl.TRIANGLES, scene.indices.length, gl.UNSIGNED_INT, 0);
      }
      gl.disable(gl.SCISSOR_TEST);
      const px = new Uint8Array(4);
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);  // waits for the GPU
    },
    // The skinned positions of every vertex of `which` by `method`: transform feedback, rasterizer off.
    async readback(which, method) {
      const scene = gpu[which].scene;
      const out = gl.createBuffer();
      gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, out);
      gl.bufferData(gl.TRANSFORM_FEEDBACK_BUFFER, 12 * scene.vertexCount, gl.STATIC_READ);
      const tf = gl.createTransformFeedback();
      gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, tf);
      gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, 0, out);
      this.bind(which, method, NO_HEAT);
      gl.uniformMatrix4fv(loc.u_view_proj, false, new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]));
      gl.uniform3fv(loc.u_light, [0, 0, 1]);
      gl.enable(gl.RASTERIZER_DISCARD);
      gl.beginTransformFeedback(gl.POINTS);
      gl.drawArrays(gl.POINTS, 0, scene.vertexCount);
      gl.endTransformFeedback();
      gl.disable(gl.RASTERIZER_DISCARD);
      gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, null);
      const got = new Float32Array(3 * scene.vertexCount);
      gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, out);
      gl.getBufferSubData(gl.TRANSFORM_FEEDBACK_BUFFER, 0, got);
      gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, null);
      gl.deleteBuffer(out);
      gl.deleteTransformFeedback(tf);
      return got;
    },
  };
}

// ---- WebGPU: skin.wgsl (with the generated blends and the table's skin()): a render pipeline and a compute
// pipeline.
// present "canvas": draw into the canvas's WebGPU context. "copy": draw into a texture, read it back and put
// it into a 2D canvas; slower, but headless Chromium (no compositor) loses the WebGPU instance on the first
// frame presented to a canvas (the next await fails with "A valid external Instance reference no longer
// exists") and leaves the page unable to show any canvas after it, while a device that never touches a
// canvas keeps working. main() tries "canvas" first, except in headless Chromium, where it uses "copy".
async function createWebGPU(canvas, present) {
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) return null;
  const device = await adapter.requestDevice();
  const context = present === "canvas" ? canvas.getContext("webgpu") : canvas.getContext("2d");
  const format = present === "canvas" ? navigator.gpu.getPreferredCanvasFormat() : "rgba8unorm";
  if (present === "canvas") context.configure({device, format, alphaMode: "opaque"});
  let target = null;  // the "copy" path's colour texture
  device.pushErrorScope("validation");
  const module = device.createShaderModule({code: $("wgsl").textContent});
  const errors = (await module.getCompilationInfo()).messages.filter((m) => m.type === "error");
  if (errors.length) throw new Error("WGSL: " + errors.map((m) => m.lineNum + ":" + m.linePos + " " + m.message).join("; "));
  const render = device.createRenderPipeline({
    layout: "auto",
    vertex: {module, entryPoint: "vs_main"},
    fragment: {module, entryPoint: "fs_main", targets: [{format}]},
    primitive: {topology: "triangle-list"},
    depthStencil: {format: "depth24plus", depthWriteEnabled: true, depthCompare: "less"},
  });
  const compute = device.createComputePipeline({layout: "auto", compute: {module, entryPoint: "cs_skin"}});
  const err = await device.popErrorScope();
  if (err) throw new Error("WebGPU validation: " + err.message);

  const buffer = (data, usage) => {
    const b = device.createBuffer({size: Math.max(16, Math.ceil(data.byteLength / 4) * 4), usage: usage | GPUBufferUsage.COPY_DST});
    device.queue.writeBuffer(b, 0, data);
    return b;
  };
  function upload(scene) {
    const g = {
      scene,
      verts: buffer(scene.vertices, GPUBufferUsage.STORAGE),
      index: buffer(scene.indices, GPUBufferUsage.INDEX),
      palette: device.createBuffer({size: 4 * scene.floatsPerPalette, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST}),
      skinned: device.createBuffer({size: 12 * scene.vertexCount, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC}),
      uniforms: [], renderGroups: [], computeGroups: [],
    };
    for (let m = 0; m < METHODS.length; ++m) {
      const u = device.createBuffer({size: 128, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST});
      g.uniforms.push(u);
      g.renderGroups.push(device.createBindGroup({layout: render.getBindGroupLayout(0), entries: [
        {binding: 0, resource: {buffer: u}}, {binding: 1, resource: {buffer: g.palette}},
        {binding: 2, resource: {buffer: g.verts}}]}));
      g.computeGroups.push(device.createBindGroup({layout: compute.getBindGroupLayout(0), entries: [
        {binding: 0, resource: {buffer: u}}, {binding: 1, resource: {buffer: g.palette}},
        {binding: 2, resource: {buffer: g.verts}}, {binding: 3, resource: {buffer: g.skinned}}]}));
    }
    return g;
  }
  const gpu = {character: upload(character), twist: upload(twist)};
  function writeUniforms(g, m, vp, heat) {
    const data = new ArrayBuffer(128), f = new Float32Array(data), i = new Int32Array(data);
    f.set(vp, 0);
    f.set(METHODS[m].colour, 16);
    f.set(normalize3([0.3, 0.5, 0.8]), 20);
    i[24] = m, i[25] = heat.on ? 1 : 0, i[26] = heat.pairs[m][0], i[27] = heat.pairs[m][1];
    f[28] = heat.scale;
    new Uint32Array(data)[29] = g.scene.vertexCount;
    i[30] = g.scene.entries;
    device.queue.writeBuffer(g.uniforms[m], 0, data);
  }
  let depth = null;
  const info = adapter.info || {};
  return {
    name: "webgpu",
    describe: () => "WebGPU: " + [info.vendor, info.architecture, info.description].filter(Boolean).join(" / ") +
                    (present === "copy" ? " (frames copied into a 2D canvas)" : ""),
    setPalette(which, floats) { device.queue.writeBuffer(gpu[which].palette, 0, floats); },
    async draw(which, heat) {
      const g = gpu[which];
      if (!depth || depth.width !== canvas.width || depth.height !== canvas.height) {
        depth = device.createTexture({size: [canvas.width, canvas.height], format: "depth24plus", usage: GPUTextureUsage.RENDER_ATTACHMENT});
        if (present === "copy")
          target = device.createTexture({size: [canvas.width, canvas.height], format, usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC});
      }
      const pw = Math.floor(canvas.width / METHODS.length), h = canvas.height;
      const vp = viewProjection(g.scene, pw / h, true);
      for (let m = 0; m < METHODS.length; ++m) writeUniforms(g, m, vp, heat);
      const enc = device.createCommandEncoder();
      const pass = enc.beginRenderPass({
        colorAttachments: [{view: (present === "canvas" ? context.getCurrentTexture() : target).createView(), loadOp: "clear", storeOp: "store",
                            clearValue: {r: 0.12, g: 0.12, b: 0.14, a: 1}}],
        depthStencilAttachment: {view: depth.createView(), depthLoadOp: "clear", depthStoreOp: "store", depthClearValue: 1},
      });
      pass.setPipeline(render);
      pass.setIndexBuffer(g.index, "uint32");
      for (let m = 0; m < METHODS.length; ++m) {
        pass.setViewport(m * pw, 0, pw, h, 0, 1);
        pass.setScissorRect(m * pw, 0, pw, h);
        pass.setBindGroup(0, g.renderGroups[m]);
        pass.drawIndexed(g.scene.indices.length);
      }
      pass.end();
      if (present === "canvas") {
        device.queue.submit([enc.finish()]);
        await device.queue.onSubmittedWorkDone();
        return;
      }
      const w = canvas.width, h2 = canvas.height, row = Math.ceil(4 * w / 256) * 256;
      const read = device.createBuffer({size: row * h2, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST});
      enc.copyTextureToBuffer({texture: target}, {buffer: read, bytesPerRow: row}, [w, h2]);
      device.queue.submit([enc.finish()]);
      await read.mapAsync(GPUMapMode.READ);
      const bytes = new Uint8Array(read.getMappedRange());
      const image = new ImageData(w, h2);
      for (let y = 0; y < h2; ++y) image.data.set(bytes.subarray(y * row, y * row + 4 * w), 4 * w * y);
      read.unmap();
      read.destroy();
      context.putImageData(image, 0, 0);
    },
    async readback(which, method) {
      const g = gpu[which];
      writeUniforms(g, method, new Float32Array(16), NO_HEAT);
      const bytes = 12 * g.scene.vertexCount;
      const read = device.createBuffer({size: bytes, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST});
      const enc = device.createCommandEncoder();
      const pass = enc.beginComputePass();
      pass.setPipeline(compute);
      pass.setBindGroup(0, g.computeGroups[method]);
      pass.dispatchWorkgroups(Math.ceil(g.scene.vertexCount / 64));
      pass.end();
      enc.copyBufferToBuffer(g.skinned, 0, read, 0, bytes);
      device.queue.submit([enc.finish()]);
      await read.mapAsync(GPUMapMode.READ);
      const got = new Float32Array(read.getMappedRange().slice(0));
      read.unmap();
      read.destroy();
      return got;
    },
  };
}

// ---- the page
// The heat map's reference (web/ui.js, heatPairs): dqs, the established volume-keeping method, so that
// red marks where a method departs from it (the candy wrapper of lbs and cga-points on the twist strip).
const state = {scene: "character", playing: true, time: 0, weight: 0, mode: 0, twist: 0,
               heat: {on: false, ref: Math.max(0, METHODS.findIndex((m) => m.name === "dqs")), scale: 0.01}};
let frameMs = null;  // smoothed time of one frame (draw calls + waiting for the GPU)

// The heat map as the renderers take it: pairs[m] = [a, b], the two methods panel m's colours compare.
function heatUniforms(scene) {
  return {on: state.heat.on, pairs: heatPairs(state.heat),
          scale: state.heat.scale * (scene === "twist" ? CGA_DATA.twist.size : CGA_DATA.size)};
}
const NO_HEAT = {on: false, pairs: METHODS.map((_, m) => [m, m]), scale: 1};

// Set when the picture must be drawn again (a control, the camera, the canvas size, the animation): a still
// pose is not redrawn every frame, which keeps a laptop cool and a virtual-time screenshot quick.
let dirty = true;

function resize(canvas) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(4, Math.floor(canvas.clientWidth * dpr)), h = Math.max(1, Math.floor(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== h) canvas.width = w, canvas.height = h, dirty = true;
}

// Max distance between the GPU's and the CPU's skinned positions over every method, relative to the size.
// shift = 1 compares method m with the next method's reference (the mismatch check).
async function selftest(renderer, shift) {
  const mode = CGA_DATA.modes.indexOf(CGA_DATA.selftest.mode);
  renderer.setPalette("character", characterPalette(mode, CGA_DATA.selftest.time, CGA_DATA.selftest.weight));
  renderer.setPalette("twist", twistPalette(CGA_DATA.twist.angles - 1));
  const cases = [["character", decodeFloats(CGA_DATA.selftest.reference), character.vertexCount, CGA_DATA.size],
                 ["twist", decodeFloats(CGA_DATA.twist.reference), twist.vertexCount, CGA_DATA.twist.size]];
  const details = [];
  let worst = 0;
  for (const [which, ref, n, size] of cases) {
    for (let m = 0; m < METHODS.length; ++m) {
      const got = await renderer.readback(which, m);
      let dev = 0;
      for (let v = 0; v < n; ++v) {
        const r = 3 * (((m + shift) % METHODS.length) * n + v);
        const d = Math.hypot(got[3 * v] - ref[r], got[3 * v + 1] - ref[r + 1], got[3 * v + 2] - ref[r + 2]);
        dev = Math.max(dev, Number.isFinite(d) ? d / size : Infinity);
      }
      details.push(which + "/" + METHODS[m].name + " " + dev.toExponential(2));
      worst = Math.max(worst, dev);
    }
  }
  return {worst, details};
}

// How long WebGPU may take to give its first frame (adapter, device, pipelines, one draw) before the page
// moves on. A WebGPU instance that loses its connection (headless Chromium: "A valid external Instance
// reference no longer exists") can leave its promises unresolved: without a limit the page would wait on a
// blank canvas forever.
const PROBE_MS = 8000;

function withTimeout(promise, ms, what) {
  let timer = null;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(what + " did not come back within " + ms / 1000 + " s")), ms);
  });
  return Promise.race([promise, late]).finally(() => clearTimeout(timer));
}

// WebGPU on `canvas` presented as `present`, with one frame drawn: null when there is no adapter; throws when
// something fails.
async function probeWebGPU(canvas, present) {
  const r = await createWebGPU(canvas, present);
  if (!r) return null;
  r.setPalette("character", characterPalette(0, 0, 0));
  await r.draw("character", heatUniforms("character"));
  return r;
}

async function main() {
  const canvas = $("view");
  resize(canvas);
  labelPanels();
  const options = new Set(location.hash.replace(/^#/, "").split("&"));
  const test = options.has("selftest");
  // A canvas keeps the first kind of context it gave: each new attempt gets a fresh canvas.
  const freshCanvas = () => {
    const c = document.createElement("canvas");
    c.id = "view";
    $("view").replaceWith(c);
    resize(c);
    return c;
  };
  let renderer = null, why = "";  // why: the reason WebGPU is not used ("" when it is, or when not asked for)
  if (options.has("webgl2")) {
    why = "";
  } else if (!navigator.gpu) {
    why = "this browser offers no WebGPU (navigator.gpu is missing)";
  } else {
    // Headless Chromium has no compositor: a WebGPU canvas loses its instance on the first frame and leaves
    // the page unable to show any later canvas, WebGL 2 included. There the page draws into a texture only.
    const presents = /HeadlessChrome/.test(navigator.userAgent) ? ["copy"] : ["canvas", "copy"];
    for (const present of presents) {
      setStatus("loading", "Loading: starting WebGPU (" + (present === "canvas" ? "drawing into the canvas" :
                "drawing into a texture copied to the canvas" + (why ? ", since drawing into the canvas failed: " + why : "")) +
                ")\u2026");
      try {
        // The self-test must test the path it was asked for, also on a busy CI machine where SwiftShader's
        // first WebGPU frame can take longer than a person would wait.
        renderer = await withTimeout(probeWebGPU(present === "canvas" ? canvas : freshCanvas(), present),
                                     test ? 5 * PROBE_MS : PROBE_MS, "the first WebGPU frame");
        if (!renderer) why = "navigator.gpu gave no adapter";
        break;
      } catch (e) {
        why = e.message;
        renderer = null;
      }
    }
    if (renderer) why = "";
  }
  if (!renderer) {
    setStatus("loading", "Loading: starting WebGL 2" + (why ? " (WebGPU not used: " + why + ")" : "") + "\u2026");
    try {
      renderer = await createWebGL2(why ? freshCanvas() : canvas);
    } catch (e) {
      setStatus("error", "Cannot draw: " + (why ? "WebGPU not used (" + why + "), and " : "") + "WebGL 2 failed (" +
                e.message + "). Try another browser, or one with hardware acceleration on.");
      throw e;
    }
  }
  const backend = renderer.describe() + (options.has("webgl2") ? " (asked for by #webgl2)" : "") +
                  (why ? " \u2014 fell back from WebGPU: " + why : "");
  const report = (extra) => {
    // Where the panels and the legend are, for tests/web's look at a screenshot.
    noteLayout();
    document.body.dataset.panels = METHODS.length;
    setStatus(why ? "fallback" : "ready", backend + extra);
  };
  report("");
  if (options.has("heat")) $("heat").checked = true;
  if (options.has("twist")) $("scene").value = "twist";
  const update = setupControls(renderer, state);
  if (options.has("paused")) state.playing = false, $("play").textContent = "play";
  const lines = [];
  if (test) {
    const r = await selftest(renderer, options.has("mismatch") ? 1 : 0);
    const line = renderer.name + " " + (r.worst <= TOLERANCE ? "ok" : "fail") + " " + r.worst.toExponential(2);
    $("cga-result").textContent = line;
    lines.push(line, "detail " + r.details.join(", "));
    // Frame time: 8 frames of the character (a panel per method), every one waited for (1 for the mismatch
    // check, which needs no timing); the self-test's frame stays on the screen.
    state.playing = false;
    $("play").textContent = "play";
    $("time").value = CGA_DATA.selftest.time, $("weight").value = CGA_DATA.selftest.weight;
    $("mode").value = CGA_DATA.modes.indexOf(CGA_DATA.selftest.mode);
    update();
    const t0 = performance.now();
    const frames = options.has("mismatch") ? 1 : 8;
    for (let i = 0; i < frames; ++i) await renderer.draw("character", heatUniforms("character"));
    if (state.scene !== "character") await renderer.draw(state.scene, heatUniforms(state.scene));
    const ms = (performance.now() - t0) / frames;
    lines.push("frame_ms " + ms.toFixed(2) + " (" + character.vertexCount + " vertices x " + METHODS.length + " panels; " +
               renderer.describe() + ")");
    report(" \u2014 frame " + ms.toFixed(1) + " ms");
    lines.push("status " + $("status").textContent);
    return lines.join("\n");
  }
  let last = performance.now(), tick = 0, drawn = 0, loopDone = null;
  const looped = new Promise((resolve) => { loopDone = resolve; });
  const loop = async () => {
    resize($("view"));
    if (state.playing && ++tick % 4 === 0) {
      const t = $("time");
      t.value = (+t.value + 1) % CGA_DATA.times;
      update();
    }
    const t0 = performance.now();
    if (dirty) {
      dirty = false;
      try {
        await withTimeout(renderer.draw(state.scene, heatUniforms(state.scene)), PROBE_MS, "a frame");
      } catch (e) {
        setStatus("error", backend + " \u2014 stopped: " + e.message + ". Reload, or add #webgl2 to the address.");
        loopDone("interactive stopped: " + e.message);
        return;
      }
      const ms = performance.now() - t0;
      frameMs = frameMs === null ? ms : 0.9 * frameMs + 0.1 * ms;
    }
    if (t0 - last > 250) {
      last = t0;
      // (0 under a virtual clock, as in Chromium's --virtual-time-budget: no figure then)
      report(frameMs > 0 ? " \u2014 frame " + frameMs.toFixed(2) + " ms" : "");
    }
    if (++drawn === 5) loopDone("interactive " + drawn + " frames, time step " + state.time + ", frame " + frameMs.toFixed(1) + " ms");
    requestAnimationFrame(loop);
  };
  requestAnimationFrame(loop);
  return options.has("frames") ? looped : "interactive";
}

window.cgagenResult = main().catch((e) => {
  const line = "unknown fail " + String(e && e.message || e).replace(/\s+/g, " ");
  $("cga-result").textContent = line;
  if (document.body.dataset.status !== "error") setStatus("error", "The page failed: " + line.slice(13));
  return line;
});
