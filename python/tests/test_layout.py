"""The package's C declarations against the library's headers: every struct it declares has the
size and field offsets the C compiler gives it, every constant its value."""
import os
import shutil
import subprocess

import pytest

from whirl import _cdef
from whirl._lib import ffi, lib


def test_struct_layout_matches_the_headers(tmp_path, repo):
    cc = shutil.which(os.environ.get("CC", "cc")) or shutil.which("gcc")
    if cc is None:
        pytest.fail("no C compiler")
    expected, lines = [], []
    for name in _cdef.CONSTANTS:
        expected.append("%s %d" % (name, getattr(lib, name)))
        lines.append('printf("%s %%d\\n", (int)(%s));' % (name, name))
    for name in _cdef.STRUCTS:
        t = ffi.typeof(name)
        expected.append("%s %d" % (name, ffi.sizeof(t)))
        lines.append('printf("%s %%zu\\n", sizeof(%s));' % (name, name))
        for field, ft in t.fields:
            expected.append("%s.%s %d" % (name, field, ft.offset))
            lines.append('printf("%s.%s %%zu\\n", offsetof(%s, %s));' % (name, field, name, field))
    src = tmp_path / "layout.c"
    src.write_text("#include <stddef.h>\n#include <stdio.h>\n"
                   + "".join('#include "whirl/%s"\n' % h for h in sorted(
                       os.listdir(os.path.join(repo, "include", "whirl"))))
                   + "int main(void) {\n" + "\n".join(lines) + "\nreturn 0;\n}\n")
    flags = subprocess.run(["pkg-config", "--cflags", "gsl"], capture_output=True,
                           text=True).stdout.split()
    exe = tmp_path / "layout"
    subprocess.run([cc, "-std=c11", "-I", os.path.join(repo, "include"), *flags, str(src),
                    "-o", str(exe)], check=True)
    got = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout.split("\n")
    assert got[:-1] == expected
