"""The declarations of _cdef.py as a generated module, whirl/_ffi.py, written when the package is
built (python/setup.py): cffi's out-of-line ABI mode, whose module holds the declarations already
parsed into cffi's tables, so that importing it costs a few milliseconds where parsing them with
pycparser at every import costs a tenth of a second or more. The module needs no compiler and
holds no CPython extension (the wheel stays py3-none); it keeps the text it was made from
(``CDEF``), and whirl._lib uses it only when that text is _cdef.py's, parsing the declarations
itself otherwise (a stale module; a source tree, which keeps the module it makes at its first
import in build/python/)."""
import contextlib
import io
import os
import tempfile

MODULE = "whirl._ffi"


def module_text(cdef: str) -> str:
    """The text of whirl/_ffi.py for the declarations ``cdef``: cffi's emit_python_code, then
    the declarations themselves as ``CDEF``."""
    import cffi  # at build time only: pycparser parses the declarations here

    builder = cffi.FFI()
    builder.set_source(MODULE, None)
    builder.cdef(cdef)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "_ffi.py")
        with contextlib.redirect_stdout(io.StringIO()):  # its "generating ..." line
            builder.emit_python_code(path)
        with open(path) as f:
            text = f.read()
    return ("# Generated from whirl/_cdef.py when the package was built (whirl/_build.py): "
            "do not edit.\n" + text + "\nCDEF = %r\n" % cdef)


def write_module(cdef: str, path: str) -> None:
    """Writes module_text(cdef) to ``path``."""
    with open(path, "w") as f:
        f.write(module_text(cdef))
