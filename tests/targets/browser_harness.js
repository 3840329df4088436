// The page-side half of the browser checks (targets/wgsl, targets/glsl-es): runs every script's kernel on the
// GPU API of the page and sets window.cgagenResult to a promise of a text, which browser_run.py reads.
// targets_check writes the page: this file inlined after a script that defines
//   CGAGEN_API   "webgpu" (a WGSL compute shader) or "webgl2" (a GLSL ES 3.00 vertex shader, outputs captured
//                by transform feedback: WebGL 2 has no compute)
//   CGAGEN_CASES [{name, rows, nin, nout, input: base64 of rows*nin little-endian float32, code: shader text}]
// Inputs are embedded because a page opened from file:// cannot fetch().
// The text, one line each:  device DESCRIPTION | case NAME COMPILE_MS RUN_MS BASE64(rows*nout float32) |
//                           fail NAME MESSAGE | total MS
"use strict";

function cgagenDecode(b64) {
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}

function cgagenEncode(floats) {
  const bytes = new Uint8Array(floats.buffer, floats.byteOffset, floats.byteLength);
  let bin = "";
  for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(bin);
}

const oneLine = (s) => String(s).replace(/\s+/g, " ");

// WebGPU: one compute pipeline per script, a storage buffer of inputs, one of outputs, one thread per row.
async function cgagenWebGPU(lines) {
  if (!navigator.gpu) throw new Error("navigator.gpu is missing: WebGPU is not enabled in this browser");
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new Error("requestAdapter() returned null: no WebGPU adapter");
  const device = await adapter.requestDevice();
  const info = adapter.info || {};
  lines.push("device WebGPU " + oneLine([info.vendor, info.architecture, info.description].filter(Boolean).join(" / ")));
  for (const c of CGAGEN_CASES) {
    const t0 = performance.now();
    device.pushErrorScope("validation");
    const module = device.createShaderModule({code: c.code});
    const messages = (await module.getCompilationInfo()).messages.filter((m) => m.type === "error");
    if (messages.length) {
      await device.popErrorScope();
      lines.push("fail " + c.name + " WGSL: " + oneLine(messages.map((m) => m.lineNum + ":" + m.linePos + ": " + m.message).join("; ")));
      continue;
    }
    let pipeline;
    try {
      pipeline = await device.createComputePipelineAsync({layout: "auto", compute: {module, entryPoint: "cgagen_main"}});
    } catch (e) {
      await device.popErrorScope();
      lines.push("fail " + c.name + " pipeline: " + oneLine(e.message || e));
      continue;
    }
    const input = cgagenDecode(c.input);
    const outBytes = c.rows * c.nout * 4;
    const inBuf = device.createBuffer({size: input.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST});
    const outBuf = device.createBuffer({size: outBytes, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC});
    const readBuf = device.createBuffer({size: outBytes, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST});
    const bindGroup = device.createBindGroup({layout: pipeline.getBindGroupLayout(0), entries: [
      {binding: 0, resource: {buffer: inBuf}}, {binding: 1, resource: {buffer: outBuf}}]});
    const error = await device.popErrorScope();
    if (error) {
      lines.push("fail " + c.name + " validation: " + oneLine(error.message));
      continue;
    }
    const t1 = performance.now();
    device.queue.writeBuffer(inBuf, 0, input);
    const enc = device.createCommandEncoder();
    const pass = enc.beginComputePass();
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, bindGroup);
    pass.dispatchWorkgroups(Math.ceil(c.rows / 64));
    pass.end();
    enc.copyBufferToBuffer(outBuf, 0, readBuf, 0, outBytes);
    device.queue.submit([enc.finish()]);
    await readBuf.mapAsync(GPUMapMode.READ);
    const out = new Float32Array(readBuf.getMappedRange().slice(0));
    readBuf.unmap();
    const t2 = performance.now();
    lines.push("case " + c.name + " " + (t1 - t0).toFixed(1) + " " + (t2 - t1).toFixed(1) + " " + cgagenEncode(out));
  }
}

// WebGL 2: per script a program whose vertex shader reads row gl_VertexID of an R32F input texture (nin
// wide) and writes the outputs into vec4 varyings cgagen_r0.. captured by transform feedback (interleaved),
// rasterizer discarded.
async function cgagenWebGL2(lines) {
  const gl = document.createElement("canvas").getContext("webgl2");
  if (!gl) throw new Error("getContext('webgl2') returned null: no WebGL 2");
  const dbg = gl.getExtension("WEBGL_debug_renderer_info");
  lines.push("device WebGL2 " + oneLine(gl.getParameter(dbg ? dbg.UNMASKED_RENDERER_WEBGL : gl.RENDERER)) + " / " +
             oneLine(gl.getParameter(gl.SHADING_LANGUAGE_VERSION)));
  const shader = (type, src) => {
    const s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error("compile: " + oneLine(gl.getShaderInfoLog(s)));
    return s;
  };
  const fs = shader(gl.FRAGMENT_SHADER, "#version 300 es\nprecision highp float;\nout vec4 c;\nvoid main() { c = vec4(0.0); }\n");
  for (const c of CGAGEN_CASES) {
    const t0 = performance.now();
    const vec4s = Math.ceil(c.nout / 4);
    let prog;
    try {
      prog = gl.createProgram();
      gl.attachShader(prog, shader(gl.VERTEX_SHADER, c.code));
      gl.attachShader(prog, fs);
      gl.transformFeedbackVaryings(prog, Array.from({length: vec4s}, (_, i) => "cgagen_r" + i), gl.INTERLEAVED_ATTRIBS);
      gl.linkProgram(prog);
      if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error("link: " + oneLine(gl.getProgramInfoLog(prog)));
    } catch (e) {
      lines.push("fail " + c.name + " GLSL ES " + oneLine(e.message));
      continue;
    }
    const t1 = performance.now();
    const input = cgagenDecode(c.input);
    const tex = gl.createTexture();
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, tex);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.R32F, c.nin, c.rows, 0, gl.RED, gl.FLOAT, input);
    gl.useProgram(prog);
    gl.uniform1i(gl.getUniformLocation(prog, "cgagen_in"), 0);
    const buf = gl.createBuffer();
    gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, buf);
    gl.bufferData(gl.TRANSFORM_FEEDBACK_BUFFER, c.rows * vec4s * 16, gl.STATIC_READ);
    gl.bindBuffer(gl.TRANSFORM_FEEDBACK_BUFFER, null);
    const tf = gl.createTransformFeedback();
    gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, tf);
    gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, 0, buf);
    gl.enable(gl.RASTERIZER_DISCARD);
    gl.beginTransformFeedback(gl.POINTS);
    gl.drawArrays(gl.POINTS, 0, c.rows);
    gl.endTransformFeedback();
    gl.disable(gl.RASTERIZER_DISCARD);
    gl.bindBufferBase(gl.TRANSFORM_FEEDBACK_BUFFER, 0, null);
    gl.bindTransformFeedback(gl.TRANSFORM_FEEDBACK, null);
    const captured = new Float32Array(c.rows * vec4s * 4);
    gl.bindBuffer(gl.COPY_READ_BUFFER, buf);
    gl.getBufferSubData(gl.COPY_READ_BUFFER, 0, captured);
    gl.bindBuffer(gl.COPY_READ_BUFFER, null);
    const err = gl.getError();
    if (err !== gl.NO_ERROR) {
      lines.push("fail " + c.name + " WebGL error 0x" + err.toString(16));
      continue;
    }
    const out = new Float32Array(c.rows * c.nout);  // drop the vec4 padding
    for (let r = 0; r < c.rows; ++r)
      for (let k = 0; k < c.nout; ++k) out[r * c.nout + k] = captured[r * vec4s * 4 + k];
    const t2 = performance.now();
    lines.push("case " + c.name + " " + (t1 - t0).toFixed(1) + " " + (t2 - t1).toFixed(1) + " " + cgagenEncode(out));
    gl.deleteTexture(tex);
    gl.deleteBuffer(buf);
    gl.deleteTransformFeedback(tf);
    gl.deleteProgram(prog);
  }
}

window.cgagenResult = (async () => {
  const lines = [];
  const t0 = performance.now();
  try {
    await (CGAGEN_API === "webgpu" ? cgagenWebGPU(lines) : cgagenWebGL2(lines));
  } catch (e) {
    lines.push("fail * " + oneLine(e.message || e));
  }
  lines.push("total " + (performance.now() - t0).toFixed(1));
  return lines.join("\n");
})();
