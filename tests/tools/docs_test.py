#!/usr/bin/python3
"""The manual's test (tests/cli/test_docs.sh): TAP lines, then the plan.

1. The manual builds with Sphinx, warnings as errors (as `make docs` does), into BUILD/docs.
2. Every symbol the shared library exports (nm -D --defined-only BUILD/libwhirl.so) has its entry
   in the C API reference (an anchor id="c.NAME" in api/c.html), and the "@param" and "@return"
   lines of the headers' comments are rendered as its functions' fields.
3. Every block marked runnable in README.md and docs/**/*.md runs as written. The marker is the
   line `<!-- runnable -->` right before the block's opening fence:
     ```console  lines "$ COMMAND" (continued by a trailing backslash) run under sh; the lines
                 that follow a command up to the next "$ " are its expected output, compared line
                 by line (a line "..." stands for any number of lines, "..." within a line for any
                 text; no line shown: not compared);
     ```python   a script that must exit 0;
     ```pycon    a doctest (">>> " lines and their expected output);
   with `<!-- runnable: FILE -->` the block (any language) is written to FILE for the blocks
   after it.
   The blocks of one page run in order in one temporary directory, which links data/, plots/,
   examples/ and python/ of the source tree; the program is the build's, installed by
   scripts/install.sh (as `make install` runs it) into a temporary prefix (its bin/ first on PATH, PKG_CONFIG_PATH and the loader's path set),
   so that the installed data directory and pkg-config file are used as a user would use them.
   A failing block is reported as "not ok N - PAGE:LINE (block K): what differed".

Usage: docs_test.py BUILD [--no-sphinx] [--only PAGE]
"""
import doctest
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MARK = re.compile(r"^<!-- runnable(?:: ([\w.-]+))? -->$")
LINKED = ["data", "plots", "examples", "python"]
TIMEOUT = 240  # seconds per block: a block that hangs fails instead of stopping the suite

n = 0
fails = 0


def tap(ok, name):
    global n, fails
    n += 1
    if not ok:
        fails += 1
    print("%s %d - %s" % ("ok" if ok else "not ok", n, name), flush=True)


def pages():
    found = [os.path.join(ROOT, "README.md")]
    found += sorted(glob.glob(os.path.join(ROOT, "docs", "**", "*.md"), recursive=True))
    return found


def blocks(path):
    """The runnable blocks of a page: (line of the fence, language, lines, file name or None)."""
    with open(path) as f:
        lines = f.read().split("\n")
    out = []
    i = 0
    while i < len(lines):
        mark = MARK.match(lines[i].strip())
        if mark:
            j = i + 1
            while j < len(lines) and not lines[j].strip():
                j += 1
            m = re.match(r"^(`{3,}|~{3,})\s*\{?([\w-]+)\}?", lines[j]) if j < len(lines) else None
            if not m:
                out.append((i + 1, "missing", [], None))
                i += 1
                continue
            fence, lang = m.group(1), m.group(2)
            k = j + 1
            while k < len(lines) and not lines[k].startswith(fence):
                k += 1
            out.append((j + 1, lang, lines[j + 1:k], mark.group(1)))
            i = k
        i += 1
    return out


def console_steps(body):
    """(command, expected output lines or None) for each "$ " command of a console block."""
    steps = []
    i = 0
    while i < len(body):
        ln = body[i]
        if not ln.startswith("$ "):
            i += 1
            continue
        cmd = ln[2:]
        while cmd.endswith("\\") and i + 1 < len(body):
            i += 1
            cmd = cmd + "\n" + body[i]
        i += 1
        expect = []
        while i < len(body) and not body[i].startswith("$ "):
            expect.append(body[i])
            i += 1
        while expect and not expect[-1].strip():
            expect.pop()
        steps.append((cmd, expect or None))
    return steps


def matches(expect, got):
    """Line-by-line comparison with "..." standing for any number of lines."""
    if not expect:
        return not got
    if expect[0].strip() == "...":
        return any(matches(expect[1:], got[k:]) for k in range(len(got) + 1))
    return bool(got) and same_line(expect[0], got[0]) and matches(expect[1:], got[1:])


def same_line(expect, got):
    """A line as shown, where "..." inside it stands for any text (a time, a digit that varies)."""
    expect, got = expect.rstrip(), got.rstrip()
    if "..." not in expect:
        return expect == got
    pattern = ".*".join(re.escape(part) for part in expect.split("..."))
    return re.fullmatch(pattern, got) is not None


def run_console(body, cwd, env):
    for cmd, expect in console_steps(body):
        try:
            p = subprocess.run(["sh", "-c", cmd], cwd=cwd, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, timeout=TIMEOUT)
        except subprocess.TimeoutExpired:
            return "`%s` did not end within %d s" % (cmd.split("\n")[0], TIMEOUT)
        if p.returncode != 0:
            return "`%s` exited with %d: %s" % (cmd.split("\n")[0], p.returncode,
                                               p.stderr.strip()[:300])
        got = p.stdout.rstrip("\n").split("\n") if p.stdout.strip() else []
        if expect is not None and not matches(expect, got):
            return "`%s` printed %r where the page shows %r" % (
                cmd.split("\n")[0], "\n".join(got)[:400], "\n".join(expect)[:400])
    return None


def run_python(body, cwd, env):
    try:
        p = subprocess.run(["/usr/bin/python3", "-"], input="\n".join(body), cwd=cwd, env=env,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                           timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return "the script did not end within %d s" % TIMEOUT
    if p.returncode != 0:
        return "the script exited with %d: %s" % (p.returncode, p.stderr.strip()[-400:])
    return None


def run_pycon(body, cwd, env, name):
    script = ("import doctest, sys\n"
              "text = sys.stdin.read()\n"
              "t = doctest.DocTestParser().get_doctest(text, {}, %r, %r, 0)\n"
              "r = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)\n"
              "r.run(t)\n"
              "sys.exit(1 if r.failures else 0)\n") % (name, name)
    p = subprocess.run(["/usr/bin/python3", "-c", script], input="\n".join(body) + "\n", cwd=cwd,
                       env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       timeout=TIMEOUT)
    if p.returncode != 0:
        return "doctest failed: %s" % (p.stdout + p.stderr).strip()[-600:]
    return None


def install(build, prefix):
    """scripts/install.sh into prefix, as `make install` runs it, from the files already built
    (no rebuild: the program keeps the data directory it was compiled with)."""
    with open(os.path.join(ROOT, "include", "whirl", "version.h")) as f:
        v = dict(re.findall(r"#define WHIRL_VERSION_(MAJOR|MINOR|PATCH) (\d+)", f.read()))
    env = dict(os.environ, BUILD=build, VERSION="%s.%s.%s" % (v["MAJOR"], v["MINOR"], v["PATCH"]),
               MAJOR=v["MAJOR"], DESTDIR="", PREFIX=prefix, BINDIR=prefix + "/bin",
               LIBDIR=prefix + "/lib", INCLUDEDIR=prefix + "/include",
               MANDIR=prefix + "/share/man", PKGCONFIGDIR=prefix + "/lib/pkgconfig",
               DATADIR=prefix + "/share/whirl")
    p = subprocess.run(["sh", "scripts/install.sh", "install"], cwd=ROOT, env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    return p.returncode == 0, p.stdout[-400:]


def undocumented_functions(text):
    """The public functions of a header (WHIRL_API ...(...);) whose comment, the one right before
    the declaration on lines of its own, lacks an "@param NAME" line for one of the parameters,
    or an "@return" line when the function returns a value: ["NAME: what is missing", ...]."""
    out = []
    for m in re.finditer(r"^WHIRL_API\b[^;(]*?\b(\w+)\s*\(", text, re.M):
        depth, i, part, parts = 1, m.end(), "", []
        while depth:  # the parameters: split at the commas outside parentheses
            c = text[i]
            depth += {"(": 1, ")": -1}.get(c, 0)
            if depth and not (c == "," and depth == 1):
                part += c
            elif part:
                parts.append(re.sub(r"/\*.*?\*/", " ", part, flags=re.S))
                part = ""
            i += 1
        params = []
        for part in parts:
            fp = re.search(r"\(\s*\*\s*(\w+)\s*\)", part)
            name = fp.group(1) if fp else re.search(r"(\w+)\s*(\[[^\]]*\])?\s*$", part).group(1)
            if part.strip() != "void":
                params.append(name)
        before = text[:m.start()].rstrip()
        start = before.rfind("/*")
        line = before[before.rfind("\n", 0, start) + 1:start] if start >= 0 else "x"
        comment = before[start:] if before.endswith("*/") and not line.strip() else ""
        named = re.findall(r"^\s*\*?\s*@param\s+(\w+)", comment, re.M)
        missing = [p for p in params if p not in named]
        if not re.match(r"WHIRL_API\s+void\s+\w", m.group(0)) and \
                not re.search(r"^\s*\*?\s*@returns?\b", comment, re.M):
            missing.append("@return")
        if missing:
            out.append("%s: %s" % (m.group(1), ", ".join(missing)))
    return out


def main():
    args = sys.argv[1:]
    build = os.path.abspath(args[0] if args else os.path.join(ROOT, "build"))
    only = args[args.index("--only") + 1] if "--only" in args else None
    tmp = tempfile.mkdtemp(prefix="whirl-docs.")
    try:
        if "--no-sphinx" not in args:
            env = dict(os.environ, WHIRL_LIBRARY=os.path.join(build, "libwhirl.so"),
                       WHIRL_PROGRAM=os.path.join(build, "whirl"))
            p = subprocess.run(["/usr/bin/python3", "-m", "sphinx", "-b", "html", "-W",
                                "--keep-going", "-q", "-d", os.path.join(build, "docs-doctrees"),
                                os.path.join(ROOT, "docs"), os.path.join(build, "docs")],
                               env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True)
            tap(p.returncode == 0, "the manual builds with warnings as errors"
                + ("" if p.returncode == 0 else ": " + p.stdout.strip()[-1500:]))
            html = os.path.join(build, "docs", "api", "c.html")
            nm = subprocess.run(["nm", "-D", "--defined-only", os.path.join(build, "libwhirl.so")],
                                stdout=subprocess.PIPE, text=True)
            syms = sorted({f[2] for f in (ln.split() for ln in nm.stdout.splitlines())
                           if len(f) == 3 and f[1] in "TDBRW" and f[2].startswith("whirl_")})
            text = open(html).read() if os.path.exists(html) else ""
            missing = [s for s in syms if 'id="c.%s"' % s not in text]
            tap(nm.returncode == 0 and len(syms) > 0 and not missing,
                "the C API reference has all %d exported symbols%s" % (
                    len(syms), ": missing " + ", ".join(missing) if missing else ""))
            # each "@return" of a header's comment is a function's "Returns" field, and no
            # "@param" or "@return" is left as text
            want = sum(len(re.findall(r"^\s*\*\s*@returns?\b", open(h).read(), re.M))
                       for h in glob.glob(os.path.join(ROOT, "include", "whirl", "*.h")))
            got = text.count(">Returns<")
            tap(want > 0 and got == want and "@param" not in text and "@return" not in text,
                "the C API reference renders the headers' %d @return lines as fields (%d)"
                % (want, got))
        # every public function has its parameters and its value in its comment
        missing = [h.split(os.sep)[-1] + ": " + u
                   for h in sorted(glob.glob(os.path.join(ROOT, "include", "whirl", "*.h")))
                   for u in undocumented_functions(open(h).read())]
        tap(not missing, "every public function's comment has an @param line per parameter and an "
            "@return line unless it returns void%s" % (": missing " + "; ".join(missing[:10])
                                                       if missing else ""))
        prefix = os.path.join(tmp, "prefix")
        ok, log = install(build, prefix)
        tap(ok, "installed into a temporary prefix" + ("" if ok else ": " + log))
        libdir = os.path.join(prefix, "lib")
        env = dict(os.environ)
        env["PATH"] = os.path.join(prefix, "bin") + os.pathsep + env.get("PATH", "")
        env["PKG_CONFIG_PATH"] = os.path.join(libdir, "pkgconfig")
        env["LD_LIBRARY_PATH"] = libdir
        env["WHIRL_LIBRARY"] = os.path.join(libdir, "libwhirl.so")
        env["PYTHONPATH"] = os.path.join(ROOT, "python")
        env["MPLBACKEND"] = "Agg"
        env["OMP_NUM_THREADS"] = "1"
        # the test's own check: a block whose output differs from the page, or whose command
        # fails, is caught (and a matching one is not)
        probe = os.path.join(tmp, "probe")
        os.makedirs(probe)
        caught = (run_console(["$ echo 4.39", "4.3900000000000006"], probe, env) is not None
                  and run_console(["$ false"], probe, env) is not None
                  and run_console(["$ printf 'a\\nb\\nc\\n'", "a", "...", "c"], probe, env) is None
                  and run_console(["$ echo 1.2345", "1.23..."], probe, env) is None)
        tap(caught, "a changed output or a failing command is caught, a matching one passes")
        total = 0
        for page in pages():
            rel = os.path.relpath(page, ROOT)
            if only and rel != only:
                continue
            bl = blocks(page)
            if not bl:
                continue
            cwd = os.path.join(tmp, "run", rel.replace(os.sep, "_"))
            os.makedirs(cwd)
            for d in LINKED:
                os.symlink(os.path.join(ROOT, d), os.path.join(cwd, d))
            for k, (line, lang, body, fname) in enumerate(bl, 1):
                total += 1
                name = "%s:%d (block %d, %s)" % (rel, line, k, fname or lang)
                if fname:
                    # a file the blocks after it use (a C source, a scene): written as shown
                    with open(os.path.join(cwd, fname), "w") as f:
                        f.write("\n".join(body) + "\n")
                    err = None
                elif lang == "console":
                    err = run_console(body, cwd, env) if console_steps(body) else "no $ command"
                elif lang == "python":
                    err = run_python(body, cwd, env)
                elif lang == "pycon":
                    err = run_pycon(body, cwd, env, name)
                else:
                    err = "a runnable block must be console, python or pycon, not %r" % lang
                tap(err is None, name + ("" if err is None else ": " + err))
        tap(total > 0, "%d runnable blocks found" % total)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print("1..%d" % n)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
