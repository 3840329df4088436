"""Every target's output compiles without a warning at every level, under the strictest flags its toolchain has.

warnings_check.py WORKDIR TOOLS SCRIPT... : TOOLS is a comma-separated list of NAME=PATH (cgagen, cxx, nvcc,
glslang, clang, python, node, rustc, chromium, pdflatex, dot, hwy_include); an empty PATH means the tool was
not found at configure time. A SCRIPT argument is PATH or PATH@NAME@OPTIONS (OPTIONS: cgagen options with '+'
for spaces, as --uniform+M), for staged and Jacobian kernels.

For each level (-O0, -O1, -O2) every script is generated for every target, and each target's files of that
level go to its toolchain together (all kernels of a level in one translation unit, crate, shader or page:
their names differ). A target passes when the toolchain accepts the files and prints no warning; the
report gives the first lines of what it printed. A target whose toolchain is missing fails, saying what to
install: the only targets left out are those CMake did not register (cuda without nvcc), and the report
lists them. Exit status 0 when every target passes at every level. ONLY=T1,T2 in the environment restricts
the run to those targets (for a rerun by hand).

Flags, per toolchain (why: each is the set a user's strict build turns on):
  cpp, simd  g++ -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wdouble-promotion -Wold-style-cast
             -Wuseless-cast -Wcast-qual -Wunused -Werror
  cuda       nvcc -Werror all-warnings, the host compiler with -Wall -Wextra -Wshadow
  glsl, glsl-es, hlsl  glslangValidator (GLSL 3.30 / ES 3.00 / HLSL -D): any WARNING fails
  opencl     clang -x cl -cl-std=CL1.2 -Wall -Wextra -Wpedantic -Werror
  python     python3 -W error (py_compile) and pyflakes
  javascript node --check on the ES module (strict mode)
  rust       rustc -D warnings (the crate lints, unused code included: the file allows only non-snake-case
             names, which are the script's)
  wgsl       Chromium's WebGPU (Tint): any message of getCompilationInfo() fails
  latex      pdflatex -halt-on-error: any "Warning" in the log fails
  dot        dot -Tsvg: anything on stderr fails
"""
import json
import os
import shutil
import subprocess
import sys

LEVELS = ("-O0", "-O1", "-O2")


def run(cmd, cwd=None, timeout=600):
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
    return p.returncode, p.stdout.decode("utf-8", "replace")


def generate(tools, work, scripts, target, level):
    """Generates every script for target at level into work; returns [(kernel name, path)]."""
    ext = run([tools["cgagen"], "--target-extension", target])[1].strip()
    out = []
    for spec in scripts:
        path, name, options = (spec.split("@") + ["", ""])[:3]
        name = name or os.path.splitext(os.path.basename(path))[0]
        dest = os.path.join(work, name + ext)
        cmd = [tools["cgagen"], level, "--target", target, "--name", name, "-o", dest]
        cmd += [o for o in options.split("+") if o] + [path]
        rc, text = run(cmd)
        if rc != 0:
            raise RuntimeError("cgagen %s --target %s %s: %s" % (level, target, spec, text))
        out.append((name, dest))
    return out


def need(tools, *names):
    missing = [n for n in names if not tools.get(n)]
    if missing:
        return "not found at configure time: %s (scripts/setup.sh installs it)" % ", ".join(missing)
    return None


def one_unit(work, files, head, tail, ext, include=True):
    """All files of a level in one source: #include lines (C++), else their text (shaders, OpenCL C)."""
    src = os.path.join(work, "all" + ext)
    with open(src, "w") as f:
        f.write(head)
        for _, path in files:
            if include:
                f.write('#include "%s"\n' % path)
            else:
                with open(path) as g:
                    f.write(g.read() + "\n")
        f.write(tail)
    return src


STRICT_CXX = ["-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Wshadow", "-Wconversion", "-Wdouble-promotion",
              "-Wold-style-cast", "-Wuseless-cast", "-Wcast-qual", "-Wunused", "-Werror", "-fsyntax-only"]


def check_cpp(tools, work, files):
    src = one_unit(work, files, "", "int main() { return 0; }\n", ".cpp")
    return run([tools["cxx"]] + STRICT_CXX + [src])


def check_simd(tools, work, files):
    src = one_unit(work, files, "", "int main() { return 0; }\n", ".cpp")
    return run([tools["cxx"]] + STRICT_CXX + ["-I" + work, src])


def check_cuda(tools, work, files):
    src = one_unit(work, files, "", "int main() { return 0; }\n", ".cu")
    return run([tools["nvcc"], "-std=c++17", "-Werror", "all-warnings", "-Xcompiler", "-Wall,-Wextra,-Wshadow",
                "-c", "-o", os.path.join(work, "all.o"), src])


def glslang(tools, src, args):
    rc, text = run([tools["glslang"]] + args + [src])
    return (1 if "WARNING" in text else rc), text


def check_glsl(tools, work, files):
    return glslang(tools, one_unit(work, files, "#version 330\n", "void main() {}\n", ".vert", include=False), [])


def check_glsl_es(tools, work, files):
    src = one_unit(work, files, "#version 300 es\nprecision highp float;\nprecision highp int;\n", "void main() {}\n",
                   ".vert", include=False)
    return glslang(tools, src, [])


def check_hlsl(tools, work, files):
    src = one_unit(work, files, "", "[numthreads(1, 1, 1)] void main() {}\n", ".hlsl", include=False)
    return glslang(tools, src, ["-D", "-S", "comp", "-e", "main", "-V", "-o", os.path.join(work, "all.spv")])


def check_opencl(tools, work, files):
    src = one_unit(work, files, "", "", ".cl", include=False)
    return run([tools["clang"], "-x", "cl", "-cl-std=CL1.2", "-Xclang", "-finclude-default-header", "-fsyntax-only",
                "-Wall", "-Wextra", "-Wpedantic", "-Werror", src])


def check_python(tools, work, files):
    paths = [p for _, p in files]
    rc, text = run([tools["python"], "-W", "error", "-m", "py_compile"] + paths)
    if rc != 0:
        return rc, text
    return run([tools["python"], "-m", "pyflakes"] + paths)


def check_javascript(tools, work, files):
    for _, path in files:
        rc, text = run([tools["node"], "--check", path])
        if rc != 0 or text.strip():
            return 1, text
    return 0, ""


def check_rust(tools, work, files):
    src = os.path.join(work, "lib.rs")
    with open(src, "w") as f:
        for name, path in files:
            f.write('#[path = "%s"]\npub mod %s;\n' % (path, "k_" + name))
    return run([tools["rustc"], "--edition", "2021", "--crate-type", "lib", "--emit", "metadata", "-D", "warnings",
                "-o", os.path.join(work, "lib.rmeta"), src])


WGSL_PAGE = """<!doctype html><html><body><script>
const CASES = %s;
window.cgagenResult = (async () => {
  const adapter = await navigator.gpu.requestAdapter();
  const device = await adapter.requestDevice();
  const lines = [];
  for (const c of CASES) {
    const messages = (await device.createShaderModule({code: c.code}).getCompilationInfo()).messages;
    for (const m of messages) lines.push(c.name + ":" + m.lineNum + ":" + m.linePos + ": " + m.type + ": " + m.message);
  }
  lines.push("done " + CASES.length);
  return lines.join("\\n");
})();
</script></body></html>
"""


def check_wgsl(tools, work, files):
    cases = [{"name": name, "code": open(path).read()} for name, path in files]
    page = os.path.join(work, "all.html")
    with open(page, "w") as f:
        f.write(WGSL_PAGE % json.dumps(cases))
    out = os.path.join(work, "all.txt")
    rc, text = run([tools["python"], tools["browser_run"], tools["chromium"], "webgpu", page, out, "120"])
    if rc != 0:
        return rc, text
    result = open(out).read()
    return (0 if result.strip() == "done %d" % len(files) else 1), result


def check_latex(tools, work, files):
    for _, path in files:
        rc, text = run([tools["pdflatex"], "-interaction=nonstopmode", "-halt-on-error", "-output-directory", work,
                        path], cwd=work)
        log = open(os.path.splitext(path)[0] + ".log", errors="replace").read()
        if rc != 0 or "Warning" in log:
            return 1, "\n".join(l for l in log.splitlines() if "Warning" in l or l.startswith("!")) or text
    return 0, ""


def check_dot(tools, work, files):
    for _, path in files:
        rc, text = run([tools["dot"], "-Tsvg", "-o", os.devnull, path])
        if rc != 0 or text.strip():
            return 1, text
    return 0, ""


# target: (tools it needs, check)
CHECKS = {
    "cpp": (("cxx",), check_cpp),
    "simd": (("cxx",), check_simd),
    "cuda": (("nvcc",), check_cuda),
    "glsl": (("glslang",), check_glsl),
    "glsl-es": (("glslang",), check_glsl_es),
    "hlsl": (("glslang",), check_hlsl),
    "opencl": (("clang",), check_opencl),
    "python": (("python",), check_python),
    "javascript": (("node",), check_javascript),
    "rust": (("rustc",), check_rust),
    "wgsl": (("chromium", "python"), check_wgsl),
    "latex": (("pdflatex",), check_latex),
    "dot": (("dot",), check_dot),
}


def main():
    work, tool_list, scripts = sys.argv[1], sys.argv[2], sys.argv[3:]
    tools = dict(t.split("=", 1) for t in tool_list.split(",") if t)
    tools["browser_run"] = os.path.join(os.path.dirname(os.path.abspath(__file__)), "browser_run.py")
    targets = [t for t in run([tools["cgagen"], "--target", "list"])[1].split()]
    targets = [t for t in targets if not os.environ.get("ONLY") or t in os.environ["ONLY"].split(",")]
    failed = []
    for target in targets:
        if target not in CHECKS:
            failed.append(target)
            print("FAIL %s: no check in warnings_check.py" % target)
            continue
        names, check = CHECKS[target]
        if target == "cuda" and not tools.get("nvcc"):
            print("cuda: not checked (nvcc not found at configure time; tests/kernels says the same)")
            continue
        missing = need(tools, *names)
        if missing:
            failed.append(target)
            print("FAIL %s: %s" % (target, missing))
            continue
        for level in LEVELS:
            dir_ = os.path.join(work, target, level.lstrip("-"))
            shutil.rmtree(dir_, ignore_errors=True)
            os.makedirs(dir_)
            files = generate(tools, dir_, scripts, target, level)
            rc, text = check(tools, dir_, files)
            if rc != 0:
                failed.append("%s %s" % (target, level))
                print("FAIL %s %s (%d kernels):\n%s" % (target, level, len(files), "\n".join(text.splitlines()[:30])))
            else:
                print("ok %s %s (%d kernels)" % (target, level, len(files)))
    print("warnings: %s" % ("FAILED: " + ", ".join(failed) if failed else "every target clean at every level"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
