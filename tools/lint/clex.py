"""Tiny C lexer shared by the lint scripts (comment stripping, pp-tokens, float classification).

Only what the proofs of spec 00 §4 need: it is not a C parser. Standard library only.
"""
import re

# Identifiers that name a floating (or complex/decimal) type in C99 or a GNU extension.
FLOAT_TYPE_WORDS = frozenset((
    "float", "double", "_Complex", "_Imaginary", "complex", "imaginary",
    "_Float16", "_Float32", "_Float64", "_Float128", "_Float32x", "_Float64x", "_Float128x",
    "__float80", "__float128", "__ibm128", "__fp16", "__bf16",
    "_Decimal32", "_Decimal64", "_Decimal128",
))

_TOKEN = re.compile(r"""
     (?P<str>(?:u8|[uUL])?"(?:\\.|[^"\\\n])*"?)
    |(?P<chr>[uUL]?'(?:\\.|[^'\\\n])*'?)
    |(?P<num>\.?[0-9](?:[eEpP][+-]|[0-9A-Za-z_.])*)
    |(?P<id>[A-Za-z_$][A-Za-z_0-9$]*)
    |(?P<nl>\n)
    |(?P<ws>[ \t\r\f\v]+)
    |(?P<other>.)
""", re.X)


def strip_comments(text):
    """Replace comments by one space, keeping every newline so line numbers stay valid.

    Line splices (backslash-newline) are replaced by a space and a newline for the same reason.
    String and character literals are kept as they are.
    """
    out = []
    i = 0
    n = len(text)
    while i < n:
        c = text[i]
        if c == "\\" and i + 1 < n and text[i + 1] == "\n":
            out.append(" \n")
            i += 2
        elif c == "/" and i + 1 < n and text[i + 1] == "*":
            j = text.find("*/", i + 2)
            if j < 0:
                j = n - 2
            out.append(" " + "\n" * text.count("\n", i, j + 2))
            i = j + 2
        elif c == "/" and i + 1 < n and text[i + 1] == "/":
            j = text.find("\n", i)
            if j < 0:
                j = n
            # a splice continues a // comment onto the next line
            while j > 0 and j < n and text[j - 1] == "\\":
                k = text.find("\n", j + 1)
                if k < 0:
                    k = n
                out.append("\n")
                j = k
            out.append(" ")
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(text[i:j + 1])
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def tokens(text, first_line=1):
    """Yield (kind, value, line) for the pp-tokens of comment-free text (no whitespace/newlines)."""
    line = first_line
    for m in _TOKEN.finditer(text):
        kind = m.lastgroup
        if kind == "nl":
            line += 1
            continue
        if kind == "ws":
            continue
        yield kind, m.group(), line


def is_float_ppnumber(s):
    """True if the preprocessing number s is a floating constant (C99 6.4.4.2)."""
    low = s.lower()
    if low.startswith("0x"):
        return "." in low or "p" in low
    return "." in low or "e" in low


def float_findings(kind, value):
    """Return a description if this token is forbidden by the no-float proof, else None."""
    if kind == "id" and value in FLOAT_TYPE_WORDS:
        return "floating type keyword '%s'" % value
    if kind == "num" and is_float_ppnumber(value):
        return "floating literal '%s'" % value
    return None


_DIRECTIVE = re.compile(r"^[ \t]*#[ \t]*([A-Za-z_]\w*)?(.*)$")


def directive(line_text):
    """(name, rest) if the line is a preprocessing directive, else None. name may be ''."""
    m = _DIRECTIVE.match(line_text)
    if not m:
        return None
    return (m.group(1) or ""), m.group(2)
