"""User-supplied text made safe to print outside JSON (the rules of the C helper
sva_text_escape() in port/json/include/sva/sva_text.h).

A mission name, a file name or an argument may hold a newline or a terminal escape
sequence; printed raw, it forges output lines or drives the terminal. `shown()` keeps
printable ASCII (backslash included) and printable characters from U+00A0 up; \\n, \\r
and \\t become two characters; every other control character (C0, DEL, C1) and every
byte that was not UTF-8 (a surrogate-escaped argument or file name) becomes \\xHH per
UTF-8 byte. Escaping the result again changes nothing.
"""
from __future__ import annotations

_SHORT = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def shown(text: object) -> str:
    out = []
    for ch in str(text):
        o = ord(ch)
        if ch in _SHORT:
            out.append(_SHORT[ch])
        elif 0xDC80 <= o <= 0xDCFF:  # a byte os.fsdecode could not decode
            out.append(f"\\x{o - 0xDC00:02x}")
        elif o < 0x20 or o == 0x7F or 0x80 <= o <= 0x9F or 0xD800 <= o <= 0xDFFF:
            out.extend(f"\\x{b:02x}" for b in ch.encode("utf-8", "surrogatepass"))
        else:
            out.append(ch)
    return "".join(out)
