#!/usr/bin/python3
"""The device-code idiom of docs/architecture.md, checked in the libraries' sources (core, libcip, libfdem, libibm).

Usage: scripts/check-idiom.py [--root DIR]   (default: this repository)

Rules, each reported as FILE:LINE: RULE: what:
  thrust     no Thrust call or include outside core/include/blastsim/core/backend.hpp: device algorithms go through
             its labelled wrappers (stable_sort_by_key, lower_bounds, exclusive_scan_total, select_indices, ...),
             which count their own host waits;
  lambda     no kernel lambda (`[...] BLAST_HD`) in library code: kernels are functors in *_kernels.hpp;
  functor    a kernel functor (a struct with a BLAST_HD operator()) lives in a *_kernels.hpp header;
  pointer    no raw-pointer member in a device struct (one with BLAST_HD members): kernels take the views of field
             lists (core/access.hpp), whose pointers the macros generate;
  array      no DeviceVector declared outside a field list's storage (core/device_groups.hpp): every device array
             is an entry of a field list.
ALLOWED below lists the exceptions, each with its reason. Exit 0: none found; 1: violations (listed); 2: bad
arguments. Needs only Python 3.
"""
import argparse
import re
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
LIBRARIES = ("core", "libcip", "libfdem", "libibm")
BACKEND = "core/include/blastsim/core/backend.hpp"
DEVICE_GROUPS = "core/include/blastsim/core/device_groups.hpp"

# (path relative to the root, rule, symbol) -> why it is allowed.
ALLOWED = {
    ("core/include/blastsim/core/field2d.hpp", "pointer", "Field2D::data"):
        "the 2-D view itself: every field list's Field2D member is one",
    (BACKEND, "pointer", "FillWith::out"): "the backend's own fill of an array (fill_device)",
    (BACKEND, "pointer", "IndexOf::out"): "the backend's own index fill (fill_indices)",
    ("libibm/include/blastsim/ibm/coupling_kernels.hpp", "pointer", "FieldOf::records"):
        "a sum of one field of the records of any ledger (generic in the record type): one view of one array",
}


def strip_code(text):
    """The text with comments, string and character literals and preprocessor lines blanked, newlines kept (so
    that line numbers stay), in one pass."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            out.append(c)
            i += 1
            continue
        if line_start and c == "#":  # a preprocessor line, with its continuations
            while i < n:
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append("\n")
                    i += 2
                    continue
                if text[i] == "\n":
                    break
                out.append(" ")
                i += 1
            continue
        line_start = False
        if c == "/" and text.startswith("//", i):
            while i < n and text[i] != "\n":
                out.append(" ")
                i += 1
            continue
        if c == "/" and text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.extend("\n" if ch == "\n" else " " for ch in text[i:end])
            i = end
            continue
        if c in "\"'":
            quote, j = c, i + 1
            while j < n and text[j] != quote:
                j += 2 if text[j] == "\\" else 1
            out.append(quote + " " * (min(j, n - 1) - i - 1) + quote)
            i = j + 1
            continue
        if c == "\n":
            line_start = True
        out.append(c)
        i += 1
    return "".join(out)


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


def matching_brace(text, open_pos):
    depth = 0
    for k in range(open_pos, len(text)):
        if text[k] == "{":
            depth += 1
        elif text[k] == "}":
            depth -= 1
            if depth == 0:
                return k
    return len(text) - 1


STRUCT = re.compile(r"\b(struct|class)\s+(\w+)(?:(?!\b(?:struct|class)\b)[^;{()])*\{")


def device_structs(code):
    """(name, body start, body end) of every struct or class whose own body (not a nested one's) uses BLAST_HD."""
    for m in STRUCT.finditer(code):
        open_pos = m.end() - 1
        close = matching_brace(code, open_pos)
        body = code[open_pos + 1:close]
        # the body less its nested braces' contents (function bodies, nested types)
        flat, depth = [], 0
        for ch in body:
            if ch == "{":
                depth += 1
                flat.append(";" if depth == 1 else "")
                continue
            if ch == "}":
                depth -= 1
                continue
            flat.append(ch if depth == 0 else ("\n" if ch == "\n" else " "))
        yield m.group(2), open_pos + 1, "".join(flat)


def pointer_members(flat):
    """(offset in the flattened body, member) of each raw-pointer data member among its top-level statements."""
    found, pos = [], 0
    for stmt in flat.split(";"):
        start = pos + len(stmt) - len(stmt.lstrip())
        pos += len(stmt) + 1
        s = stmt.strip()
        if not s or "BLAST_HD" in s or s.startswith(("using", "typedef", "friend", "static constexpr", "template")):
            continue
        s = re.sub(r"^(public|private|protected)\s*:", "", s).strip()
        s = s.split("=")[0]
        if "::*" in s or "operator" in s:
            continue
        if "(" in s and "(*" not in s:  # a function declaration
            continue
        if "*" in s:
            names = re.findall(r"\*\s*(?:const\s+)?(\w+)", s)
            found.append((start, ", ".join(names) or s))
    return found


DEVICE_VECTOR = re.compile(r"\bDeviceVector\s*<")


def device_vector_declarations(code):
    """(position, name) of each DeviceVector declared (not a reference, pointer or parameter's type)."""
    out = []
    for m in DEVICE_VECTOR.finditer(code):
        depth, k = 1, m.end()
        while k < len(code) and depth:
            depth += {"<": 1, ">": -1}.get(code[k], 0)
            k += 1
        rest = code[k:k + 200]
        d = re.match(r"\s*(\w+)\s*([;,({=\[])", rest)
        if not d:
            continue  # `>&`, `>*`, `>>`, a template argument
        if d.group(2) == "(" and re.match(r"\s*\w+\s*\([^)]*\)\s*(const\s*)?\{", rest):
            continue  # a function returning a DeviceVector
        out.append((m.start(), d.group(1)))
    return out


def check(root, full_tree=True):
    """The violations in the libraries under root; with `full_tree`, an entry of ALLOWED that nothing needs is one
    too (the list must not outlive its reasons)."""
    problems, used = [], set()
    for lib in LIBRARIES:
        for path in sorted((root / lib).rglob("*")):
            if path.suffix not in (".hpp", ".cpp", ".cu", ".cuh") or not path.is_file():
                continue
            rel = path.relative_to(root).as_posix()
            raw = path.read_text(errors="replace")
            code = strip_code(raw)

            def report(pos, rule, symbol, what):
                if (rel, rule, symbol) in ALLOWED:
                    used.add((rel, rule, symbol))
                else:
                    problems.append(f"{rel}:{line_of(code, pos)}: {rule}: {what}")

            if rel != BACKEND:
                for m in re.finditer(r"\bthrust::\w+", code):
                    report(m.start(), "thrust", m.group(0), f"{m.group(0)} (use the wrappers of {BACKEND})")
                for m in re.finditer(r"#\s*include\s*<thrust/[^>]*>", raw):
                    report(m.start(), "thrust", "include", f"Thrust included ({m.group(0)})")
            for m in re.finditer(r"\[[^\[\]]*\]\s*(\([^()]*\)\s*)?BLAST_HD\b|\[[^\[\]]*\]\s*BLAST_HD\s*\(", code):
                report(m.start(), "lambda", "", "a kernel lambda (write a functor in a *_kernels.hpp header)")
            for name, start, flat in device_structs(code):
                if re.search(r"BLAST_HD[^;{]*\boperator\s*\(\s*\)\s*\(", flat) and not rel.endswith("_kernels.hpp") \
                        and rel not in (BACKEND, "core/include/blastsim/core/field2d.hpp"):
                    report(start, "functor", name, f"kernel functor {name} outside a *_kernels.hpp header")
                if "BLAST_HD" not in flat:
                    continue
                for offset, members in pointer_members(flat):
                    symbol = f"{name}::{members}"
                    report(start + offset, "pointer", symbol,
                           f"raw-pointer member {symbol} in a device struct (take a field list's view)")
            if rel not in (BACKEND, DEVICE_GROUPS):
                for pos, name in device_vector_declarations(code):
                    report(pos, "array", name, f"DeviceVector {name} outside a field list's storage")
    if full_tree:
        for key in sorted(set(ALLOWED) - used):
            problems.append(f"{key[0]}: allowed: the exception {key[2]} ({key[1]}) is no longer needed: remove it")
    return problems


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", default=str(REPO), help="the repository to check (default: this one)")
    args = p.parse_args()
    root = Path(args.root)
    if not all((root / lib).is_dir() for lib in LIBRARIES):
        p.error(f"--root {root}: not a blastsim tree (it lacks {', '.join(LIBRARIES)})")
    problems = check(root, full_tree=root.resolve() == REPO)
    for line in problems:
        print(line)
    if problems:
        print(f"check-idiom: {len(problems)} violation(s) of the device-code idiom (docs/architecture.md)",
              file=sys.stderr)
        sys.exit(1)
    print("check-idiom: the libraries follow the device-code idiom (no Thrust outside the backend, no kernel "
          "lambda, functors in *_kernels.hpp, no raw-pointer member, every array in a field list)")


if __name__ == "__main__":
    main()
