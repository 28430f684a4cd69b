"""No panic on a path that input or the allocator can reach, in the Python
extension (python/src) and the command line (reports/src/cli and the files
it reads and writes): issue 42.

clippy enforces it (the lints below, denied in python/src/lib.rs and on the
CLI's modules in reports/src/lib.rs; the team's `cargo clippy ... -D
warnings` runs them). This test checks, without clippy, that the lints stay
denied, that every `#[allow]` of one carries a `// Justified:` comment, and
that no `unwrap()`, `expect(`, `panic!`, `unreachable!`, `todo!` or
`unimplemented!` appears outside test code there."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LINTS = ["clippy::unwrap_used", "clippy::expect_used", "clippy::panic", "clippy::indexing_slicing",
         "clippy::unreachable", "clippy::todo", "clippy::unimplemented"]
CLI_MODULES = ["array_io", "cli", "input", "npy_layout", "output"]
FORBIDDEN = re.compile(r"\.unwrap\(\)|\.expect\(|\bpanic!|\bunreachable!|\btodo!|\bunimplemented!")


def _scoped_files():
    files = sorted((ROOT / "python" / "src").glob("*.rs")) + sorted((ROOT / "reports" / "src" / "cli").glob("*.rs"))
    return files + [ROOT / "reports" / "src" / f"{m}.rs" for m in CLI_MODULES if m != "cli"]


def _code_lines(path):
    """(number, line) of the code before the file's `#[cfg(test)]` module,
    comments dropped."""
    out = []
    for k, line in enumerate(path.read_text().splitlines(), 1):
        if line.strip().startswith("#[cfg(test)]"):
            break
        code = line.split("//")[0]
        if code.strip():
            out.append((k, code))
    return out


def _denied(attrs):
    return set(re.findall(r"clippy::\w+", " ".join(a for a in attrs if "deny" in a)))


def test_the_lints_are_denied_on_the_extension_and_every_cli_module():
    ext = (ROOT / "python" / "src" / "lib.rs").read_text().splitlines()
    assert _denied([line for line in ext if line.startswith("#![deny(")]) >= set(LINTS)
    lib = (ROOT / "reports" / "src" / "lib.rs").read_text().splitlines()
    for module in CLI_MODULES:
        k = lib.index(f"pub mod {module};")
        attrs = []
        while k > 0 and lib[k - 1].startswith("#["):
            k -= 1
            attrs.append(lib[k])
        assert _denied(attrs) >= set(LINTS), module
    config = (ROOT / "clippy.toml").read_text()
    assert "allow-unwrap-in-tests = true" in config  # tests assert by panicking


def test_every_allow_of_a_no_panic_lint_is_justified():
    for path in _scoped_files():
        lines = path.read_text().splitlines()
        for k, line in enumerate(lines):
            if re.search(r"#!?\[allow\([^)]*(" + "|".join(LINTS) + r")", line):
                above = lines[max(0, k - 4):k]
                assert any("// Justified:" in a for a in above), f"{path.relative_to(ROOT)}:{k + 1}: {line.strip()}"


def test_no_unwrap_expect_or_panic_outside_tests():
    found = [f"{path.relative_to(ROOT)}:{k}: {code.strip()}" for path in _scoped_files()
             for k, code in _code_lines(path) if FORBIDDEN.search(code)]
    assert not found, "\n".join(found)
