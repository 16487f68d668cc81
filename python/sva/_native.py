"""The ctypes binding of libsva_py (python/src/sva_py.c): the core and the JSON layer."""
from __future__ import annotations

import ctypes
import os
import threading

OK = 0
FAILED = 1
BAD_INPUT = 2
BAD_ARGUMENT = 3

_ERROR_SIZE = 2048  # > the escaped form of any SVA_JSON_ERROR_SIZE message
_LIBRARY_NAME = "libsva_py.so"

_lock = threading.Lock()
_library: ctypes.CDLL | None = None


def _load() -> ctypes.CDLL:
    global _library
    with _lock:
        if _library is None:
            path = os.environ.get("SVA_PY_LIBRARY") or os.path.join(os.path.dirname(__file__),
                                                                     _LIBRARY_NAME)
            lib = ctypes.CDLL(path)
            lib.sva_py_plan.argtypes = [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_char_p,
                                        ctypes.c_char_p, ctypes.c_long,
                                        ctypes.POINTER(ctypes.c_void_p), ctypes.c_char_p,
                                        ctypes.c_size_t]
            lib.sva_py_plan.restype = ctypes.c_int
            lib.sva_py_replan.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_long,
                                          ctypes.POINTER(ctypes.c_void_p), ctypes.c_char_p,
                                          ctypes.c_size_t]
            lib.sva_py_replan.restype = ctypes.c_int
            lib.sva_py_free.argtypes = [ctypes.c_void_p]
            lib.sva_py_free.restype = None
            lib.sva_py_version.argtypes = []
            lib.sva_py_version.restype = ctypes.c_char_p
            _library = lib
        return _library


def _take(lib: ctypes.CDLL, code: int, out: ctypes.c_void_p,
          err: ctypes.Array[ctypes.c_char]) -> tuple[int, str]:
    if code != OK:
        return code, err.value.decode("utf-8", "replace")
    assert out.value is not None
    try:
        text = ctypes.string_at(out.value).decode("utf-8")
    finally:
        lib.sva_py_free(out)
    return OK, text


def plan(text: bytes, source: str, algo: str, flow_work: int) -> tuple[int, str]:
    """(OK, plan JSON text) or (code, message) for the mission document `text`."""
    lib = _load()
    out = ctypes.c_void_p()
    err = ctypes.create_string_buffer(_ERROR_SIZE)
    code = lib.sva_py_plan(text, len(text), source.encode("utf-8"), algo.encode("utf-8"),
                           flow_work, ctypes.byref(out), err, _ERROR_SIZE)
    return _take(lib, code, out, err)


def replan(path: str, algo: str, flow_work: int) -> tuple[int, str]:
    """(OK, replan JSON text) or (code, message) for the live file at `path`."""
    lib = _load()
    out = ctypes.c_void_p()
    err = ctypes.create_string_buffer(_ERROR_SIZE)
    code = lib.sva_py_replan(os.fsencode(path), algo.encode("utf-8"), flow_work,
                             ctypes.byref(out), err, _ERROR_SIZE)
    return _take(lib, code, out, err)


def core_version() -> str:
    """MAJOR.MINOR.PATCH of the core the library was built from."""
    value: bytes = _load().sva_py_version()
    return value.decode("ascii")
