#!/usr/bin/env python3
"""Checks of the workspace's layout that cargo does not make (docs/architecture.md):

1. no source file holds more than 600 lines of code (blank lines, comments and `#[cfg(test)]`
   modules aside);
2. no dependency cycle between the top-level modules of a library crate (`crate::a` used in
   module `b` is the edge b -> a; test code aside), and none between the files of any crate
   (`crate::a::b`, `super::x`, a child `x::` named in its parent, re-exports aside: a module
   that calls back into the module that dispatches to it is a cycle);
3. no flag name (`--word`) in a string literal of the maths or formats crates' code (tests
   aside): flag names are the command line's words, added as context by the commands crate
   (`flags.rs`); in the commands crate, whose requests are the command line's options (and
   Python's `process_file` keywords), every flag named is an option of a request
   (`src/args.rs`: a field, or a `long = "…"`), so no message names an option that does not
   exist.

Written apart from the Rust code it checks: a small tokenizer of Rust's comments, strings and
braces. `--self-test` runs it on small inputs whose answers are known.
Exit status 1 and one line per finding when a check fails.
"""
import re
import sys
from pathlib import Path

MAX_CODE_LINES = 600
REEXPORT = re.compile(r"\bpub(\s*\([^)]*\))?\s+use\s[^;]*;")
LIBRARY_CRATES = ["crates/inbetween", "crates/inbetween-io", "crates/inbetween-commands"]
# The crate whose requests are the command line's options: it may name them, and only them.
REQUESTS = {"crates/inbetween-commands": "src/args.rs"}
ALL_CRATES = LIBRARY_CRATES + ["crates/inbetween-cli"]
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z-]*")


def tokens(src):
    """Splits Rust source into (kind, text, line) with kind 'code', 'comment' or 'string'."""
    out = []
    i, n, line = 0, len(src), 1
    code_start = 0

    def flush_code(end):
        if end > code_start:
            out.append(("code", src[code_start:end], line_at(code_start)))

    line_starts = [0] + [m.end() for m in re.finditer("\n", src)]

    def line_at(pos):
        lo, hi = 0, len(line_starts) - 1
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if line_starts[mid] <= pos:
                lo = mid
            else:
                hi = mid - 1
        return lo + 1

    while i < n:
        c = src[i]
        if src.startswith("//", i):
            flush_code(i)
            j = src.find("\n", i)
            j = n if j < 0 else j
            out.append(("comment", src[i:j], line_at(i)))
            i = code_start = j
        elif src.startswith("/*", i):
            flush_code(i)
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif src.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append(("comment", src[i:j], line_at(i)))
            i = code_start = j
        elif (m := re.match(r'b?r(#*)"', src[i:])) and (i == 0 or not (src[i - 1].isalnum() or src[i - 1] == "_")):
            flush_code(i)
            close = '"' + m.group(1)
            j = src.find(close, i + m.end())
            j = n if j < 0 else j + len(close)
            out.append(("string", src[i:j], line_at(i)))
            i = code_start = j
        elif c == '"':
            flush_code(i)
            j = i + 1
            while j < n and src[j] != '"':
                j += 2 if src[j] == "\\" else 1
            out.append(("string", src[i : j + 1], line_at(i)))
            i = code_start = j + 1
        elif c == "'":
            # A char literal ('a', '\n', '\u{1F600}') or a lifetime ('a).
            m = re.match(r"'(\\u\{[0-9a-fA-F]+\}|\\.|[^\\'])'", src[i:])
            if m:
                flush_code(i)
                out.append(("string", m.group(0), line_at(i)))
                i = code_start = i + m.end()
            else:
                i += 1
        else:
            i += 1
    flush_code(n)
    return out


def strip_tests(toks):
    """The tokens without `#[cfg(test)]` items (a module or function and its braces)."""
    out = []
    skipping, depth, armed = False, 0, False
    for kind, text, line in toks:
        if kind != "code":
            if not skipping:
                out.append((kind, text, line))
            continue
        kept = []
        i = 0
        while i < len(text):
            if not skipping:
                m = re.compile(r"#\[cfg\(test\)\]").search(text, i)
                if not m:
                    kept.append(text[i:])
                    break
                kept.append(text[i : m.start()])
                skipping, armed, depth, i = True, False, 0, m.end()
            else:
                ch = text[i]
                if ch == "{":
                    depth, armed = depth + 1, True
                elif ch == "}":
                    depth -= 1
                    if armed and depth == 0:
                        skipping = False
                elif ch == ";" and not armed and depth == 0:
                    skipping = False  # `#[cfg(test)] mod tests;` or a `use`
                i += 1
        if kept:
            out.append((kind, "".join(kept), line))
    return out


def code_lines(toks):
    """The number of lines that hold code (or a string) once comments are gone."""
    lines = set()
    for kind, text, line in toks:
        if kind == "comment":
            continue
        for k, part in enumerate(text.split("\n")):
            if part.strip():
                lines.add(line + k)
    return len(lines)


def is_test_file(path):
    return path.name == "tests.rs" or "tests" in path.parts or "benches" in path.parts


def source_files(crate):
    return sorted(p for p in (Path(crate) / "src").rglob("*.rs") if not is_test_file(p))


def top_module(src_dir, path):
    rel = path.relative_to(src_dir)
    if rel.parts in (("lib.rs",), ("main.rs",)):
        return None
    return rel.parts[0].removesuffix(".rs")


def used_modules(code, here_is_top_file):
    """Top-level modules named by `crate::x` (and `super::x` in a top-level module's own file)."""
    found = set()
    for m in re.finditer(r"\bcrate::(\{)?", code):
        if m.group(1):
            depth, j, item = 1, m.end(), ""
            while j < len(code) and depth:
                ch = code[j]
                if ch == "{":
                    depth += 1
                elif ch == "}":
                    depth -= 1
                if depth == 1 and ch == ",":
                    found.add(item.strip().split("::")[0])
                    item = ""
                elif depth >= 1 and not (depth == 1 and ch in "{"):
                    item += ch if depth == 1 else ""
                j += 1
            found.add(item.strip().split("::")[0])
        else:
            w = re.match(r"[A-Za-z_]\w*", code[m.end() :])
            if w:
                found.add(w.group(0))
    if here_is_top_file:
        for m in re.finditer(r"\bsuper::([A-Za-z_]\w*)", code):
            found.add(m.group(1))
    found.discard("")
    return found


def module_graph(crate):
    src = Path(crate) / "src"
    tops = {top_module(src, p) for p in source_files(crate)} - {None}
    edges = {t: set() for t in tops}
    for p in source_files(crate):
        me = top_module(src, p)
        if me is None:
            continue
        toks = strip_tests(tokens(p.read_text()))
        code = " ".join(t for k, t, _ in toks if k == "code")
        top_file = len(p.relative_to(src).parts) == 1
        for other in used_modules(code, top_file):
            if other in tops and other != me:
                edges[me].add(other)
    return edges


def file_module(src_dir, path):
    """A file's module path: `a/b.rs` and `a/b/mod.rs` are ("a", "b"); lib.rs and main.rs ()."""
    parts = list(path.relative_to(src_dir).parts)
    parts[-1] = parts[-1].removesuffix(".rs")
    if parts[-1] == "mod" or parts in (["lib"], ["main"]):
        parts = parts[:-1]
    return tuple(parts)


def file_edges(modules, me, code):
    """The modules of `modules` (tuples) that the code of module `me` names."""
    found = set()

    def longest(path):
        for k in range(len(path), 0, -1):
            if tuple(path[:k]) in modules:
                return tuple(path[:k])
        return None

    for m in re.finditer(r"\b(crate|super|self)((?:::[A-Za-z_]\w*)+)", code):
        names = m.group(2).split("::")[1:]
        base = {"crate": [], "super": list(me[:-1]), "self": list(me)}[m.group(1)]
        target = longest(base + names) or tuple(base)
        found.add(target)
    for m in re.finditer(r"(?<![\w:])([A-Za-z_]\w*)::", code):
        child = me + (m.group(1),)
        if child in modules:
            found.add(child)
    # The crate root re-exports items (`crate::Fps`): naming one is no edge to lib.rs itself.
    found.discard(())
    found.discard(me)
    return {t for t in found if t in modules}


def file_graph(crate):
    src = Path(crate) / "src"
    files = source_files(crate)
    modules = {file_module(src, p) for p in files}
    edges = {"::".join(m) or "crate": set() for m in modules}
    for p in files:
        me = file_module(src, p)
        toks = strip_tests(tokens(p.read_text()))
        code = " ".join(t for k, t, _ in toks if k == "code")
        # A re-export (`pub use child::Item;`) is a facade, not a use of the child.
        code = REEXPORT.sub(" ", code)
        for t in file_edges(modules, me, code):
            edges["::".join(me) or "crate"].add("::".join(t) or "crate")
    return edges


def cycles(edges):
    """The strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def flag_names(path):
    found = []
    for kind, text, line in strip_tests(tokens(path.read_text())):
        if kind == "string":
            for m in FLAG.finditer(text):
                found.append((line, m.group(0)))
    return found


def request_options(path):
    """The long options of the requests in `path`: each `pub field:` of a struct, as kebab-case,
    and each `long = "name"`."""
    text = path.read_text()
    names = {"--" + f.replace("_", "-") for f in re.findall(r"^\s*pub (\w+):", text, re.M)}
    names |= {"--" + n for n in re.findall(r'long = "([a-z-]+)"', text)}
    return names


def check():
    problems = []
    for crate in ALL_CRATES:
        for p in source_files(crate):
            n = code_lines(strip_tests(tokens(p.read_text())))
            if n > MAX_CODE_LINES:
                problems.append(f"{p}: {n} lines of code (at most {MAX_CODE_LINES})")
    for crate in ALL_CRATES:
        for comp in cycles(file_graph(crate)):
            problems.append(f"{crate}: dependency cycle between files {', '.join(comp)}")
    for crate in LIBRARY_CRATES:
        for comp in cycles(module_graph(crate)):
            problems.append(f"{crate}: dependency cycle between modules {', '.join(comp)}")
        known = request_options(Path(crate) / REQUESTS[crate]) if crate in REQUESTS else set()
        for p in source_files(crate):
            for line, flag in flag_names(p):
                if flag not in known:
                    what = "an option no request has" if crate in REQUESTS else "a library message"
                    problems.append(f"{p}:{line}: flag name {flag} in {what}")
    for p in problems:
        print(p)
    return 1 if problems else 0


def self_test():
    src = '''// a comment with "--flag"
fn a() -> &'static str { "--key-fps" }
/* block /* nested */ --x */
const C: char = '{';
const R: &str = r#"raw "--from" "#;
#[cfg(test)]
mod tests {
    fn t() { let _ = "--in-tests"; { } }
}
fn b() {}
'''
    toks = strip_tests(tokens(src))
    strings = [t for k, t, _ in toks if k == "string"]
    assert strings == ['"--key-fps"', "'{'", 'r#"raw "--from" "#'], strings
    assert code_lines(toks) == 4, code_lines(toks)
    assert used_modules("use crate::{a::X, b, c::{d, e}}; crate::f::g();", False) == {"a", "b", "c", "f"}
    assert used_modules("use super::x::Y;", True) == {"x"}
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []
    mods = {(), ("cmd",), ("cmd", "reduce"), ("cmd", "reduce", "gltf"), ("cmd", "settings")}
    me = ("cmd", "reduce", "gltf")
    assert file_edges(mods, me, "super::report_all(x); crate::cmd::settings::glob(); ") == {
        ("cmd", "reduce"), ("cmd", "settings")}, file_edges(mods, me, "super::report_all(x)")
    assert file_edges(mods, ("cmd", "reduce"), "gltf::to_gltf(a); inbetween::x::y();") == {me}
    assert file_edges(mods, ("cmd", "reduce"), "self::gltf::X") == {me}
    assert REEXPORT.sub(" ", "pub use gltf::X; pub(crate) use a::{b, c}; use d::E;") == "    use d::E;"
    assert [m.group(0) for m in FLAG.finditer('"--fps 30, a-b--c, ---"')] == ["--fps"]
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        args = Path(d) / "args.rs"
        args.write_text('pub struct A {\n    /// doc\n    pub key_fps: Option<f64>,\n'
                        '    #[arg(short = \'o\', long = "output")]\n    pub out: Option<P>,\n}\n'
                        'fn f() { let pubx: u8 = 0; }\n')
        assert request_options(args) == {"--key-fps", "--out", "--output"}, request_options(args)
    print("layout.py self-test: ok")
    return 0


if __name__ == "__main__":
    sys.exit(self_test() if sys.argv[1:] == ["--self-test"] else check())
