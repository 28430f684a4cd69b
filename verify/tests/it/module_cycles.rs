//! No import circles: in each crate of the workspace, the file → file graph
//! of `src/` has no cycle. An edge runs from a file to the file that defines
//! what it names through a `use` declaration or a `crate::` / `super::` /
//! `self::` / child-module path, followed through re-exports (`pub use`) to
//! the definition. A file naming the modules below its own (a parent
//! calling or re-exporting its children) is structure, not an import, and
//! test code (`#[cfg(test)]`) is left out. Two files in a
//! circle cannot be read, tested or moved apart; the fix is to move what
//! they share to the lower one, or to a small module of its own.
//!
//! The graph comes from the source text (comments, strings and character
//! literals removed), not from the compiler, so the test also checks that it
//! finds known edges in the workspace and a circle hidden behind a
//! re-export in a fixture crate.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// A module's path from its crate's root (`["ndimage", "mode"]`).
type ModPath = Vec<String>;

/// File → files it imports from, as paths relative to `src/`.
type Graph = BTreeMap<String, BTreeSet<String>>;

// ---------------------------------------------------------------- lexing

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// End of a raw string (`r"…"`, `br#"…"#`) starting at `i`, if one does.
fn raw_string_end(c: &[char], i: usize) -> Option<usize> {
    if i > 0 && is_ident(c[i - 1]) {
        return None;
    }
    let mut j = i + usize::from(c[i] == 'b');
    if c.get(j) != Some(&'r') {
        return None;
    }
    j += 1;
    let hashes = c[j..].iter().take_while(|&&h| h == '#').count();
    j += hashes;
    if c.get(j) != Some(&'"') {
        return None;
    }
    let close: Vec<char> = std::iter::once('"')
        .chain(std::iter::repeat_n('#', hashes))
        .collect();
    (j + 1..c.len())
        .find(|&k| c[k..].starts_with(&close))
        .map(|k| k + close.len())
}

/// End of the string literal whose opening quote is at `i`.
fn string_end(c: &[char], i: usize) -> usize {
    let mut j = i + 1;
    while j < c.len() && c[j] != '"' {
        j += if c[j] == '\\' { 2 } else { 1 };
    }
    j + 1
}

/// End of a character literal at `i` (`'x'`, `'\n'`, `'\u{1F}'`); `None`
/// for a lifetime or a label.
fn char_end(c: &[char], i: usize) -> Option<usize> {
    if c.get(i + 1) == Some(&'\\') {
        return (i + 3..c.len()).find(|&k| c[k] == '\'').map(|k| k + 1);
    }
    (c.get(i + 2) == Some(&'\'')).then_some(i + 3)
}

/// End of the (nested) block comment starting at `i`.
fn block_comment_end(c: &[char], i: usize) -> usize {
    let (mut depth, mut j) = (0, i);
    while j < c.len() {
        if c[j..].starts_with(&['/', '*']) {
            depth += 1;
            j += 2;
        } else if c[j..].starts_with(&['*', '/']) {
            depth -= 1;
            j += 2;
            if depth == 0 {
                return j;
            }
        } else {
            j += 1;
        }
    }
    j
}

/// The source without comments and with every string or character literal
/// emptied, so that neither can add a path.
fn strip(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < c.len() {
        if c[i..].starts_with(&['/', '/']) {
            i = (i..c.len()).find(|&k| c[k] == '\n').unwrap_or(c.len());
        } else if c[i..].starts_with(&['/', '*']) {
            i = block_comment_end(&c, i);
        } else if let Some(end) = raw_string_end(&c, i) {
            out.push_str("\"\"");
            i = end;
        } else if c[i] == '"' {
            out.push_str("\"\"");
            i = string_end(&c, i);
        } else if let Some(end) = (c[i] == '\'').then(|| char_end(&c, i)).flatten() {
            out.push_str("' '");
            i = end;
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// Identifiers, numbers, `::` and single punctuation characters.
fn tokens(code: &str) -> Vec<String> {
    let c: Vec<char> = code.chars().collect();
    let mut out = vec![];
    let mut i = 0;
    while i < c.len() {
        if c[i].is_whitespace() {
            i += 1;
        } else if is_ident(c[i]) {
            let n = c[i..].iter().take_while(|&&x| is_ident(x)).count();
            out.push(c[i..i + n].iter().collect());
            i += n;
        } else if c[i..].starts_with(&[':', ':']) {
            out.push("::".into());
            i += 2;
        } else {
            out.push(c[i].to_string());
            i += 1;
        }
    }
    out
}

// ---------------------------------------------------------------- scanning

/// A path a module names.
struct Ref {
    file: String,
    module: ModPath,
    path: Vec<String>,
}

/// What the files of one crate define, import and name.
#[derive(Default)]
struct Facts {
    /// Every module (file or inline) and the file it is in.
    modules: BTreeMap<ModPath, String>,
    /// Modules declared under `#[cfg(test)]`, with all below them.
    test_modules: BTreeSet<ModPath>,
    defs: BTreeMap<ModPath, BTreeSet<String>>,
    /// `use` names at module level: name → path as written.
    uses: BTreeMap<ModPath, BTreeMap<String, Vec<String>>>,
    globs: BTreeMap<ModPath, Vec<Vec<String>>>,
    /// `macro_rules!` names and their files (`crate::name!` after
    /// `#[macro_export]`).
    macros: BTreeMap<String, String>,
    refs: Vec<Ref>,
}

const ITEM_KEYWORDS: [&str; 9] = [
    "fn", "struct", "enum", "trait", "type", "const", "static", "union", "mod",
];

/// The module of a file at `rel` (relative to `src/`, `/`-separated).
fn file_module(rel: &str) -> ModPath {
    let mut parts: Vec<String> = rel
        .trim_end_matches(".rs")
        .split('/')
        .map(String::from)
        .collect();
    if parts.len() == 1 && parts[0] == "lib" {
        parts.clear();
    }
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// The paths of a `use` tree (the tokens between `use` and `;`), each with
/// the name it brings in (`None` for a glob).
fn use_paths(toks: &[String]) -> Vec<(Vec<String>, Option<String>)> {
    fn tree(
        toks: &[String],
        mut k: usize,
        prefix: &[String],
        out: &mut Vec<(Vec<String>, Option<String>)>,
    ) -> usize {
        let mut path = prefix.to_vec();
        while k < toks.len() {
            match toks[k].as_str() {
                "{" => {
                    k += 1;
                    while k < toks.len() && toks[k] != "}" {
                        k = tree(toks, k, &path, out);
                        k += usize::from(toks.get(k).is_some_and(|t| t == ","));
                    }
                    return k + 1;
                }
                "*" => {
                    path.push("*".into());
                    out.push((path, None));
                    return k + 1;
                }
                "::" => k += 1,
                "," | "}" => break,
                "as" => {
                    out.push((path, toks.get(k + 1).cloned()));
                    return k + 2;
                }
                t => {
                    path.push(t.into());
                    k += 1;
                }
            }
        }
        if path.len() > prefix.len() {
            let name = path.last().cloned();
            out.push((path, name));
        }
        k
    }
    let mut out = vec![];
    tree(toks, 0, &[], &mut out);
    out
}

/// Where the scan of a file stands.
struct Cursor {
    base: ModPath,
    depth: usize,
    /// Inline `mod name {` blocks open: (depth outside, name).
    inline: Vec<(usize, String)>,
    /// Depth outside the `#[cfg(test)]` item being read, if any.
    test_at: Option<usize>,
    pending_test: bool,
}

impl Cursor {
    fn module(&self) -> ModPath {
        let mut m = self.base.clone();
        m.extend(self.inline.iter().map(|(_, n)| n.clone()));
        m
    }

    /// At the level of the module's items (not inside a body).
    fn at_item_level(&self) -> bool {
        self.depth == self.inline.last().map_or(0, |(d, _)| d + 1)
    }

    fn in_test(&self) -> bool {
        self.test_at.is_some() || self.pending_test
    }

    fn open(&mut self) {
        if self.pending_test && self.test_at.is_none() {
            self.test_at = Some(self.depth);
        }
        self.pending_test = false;
        self.depth += 1;
    }

    fn close(&mut self) {
        self.depth = self.depth.saturating_sub(1);
        if self.inline.last().is_some_and(|(d, _)| *d == self.depth) {
            self.inline.pop();
        }
        if self.test_at == Some(self.depth) {
            self.test_at = None;
        }
    }
}

impl Facts {
    fn define(&mut self, cur: &Cursor, name: &str) {
        if cur.at_item_level() {
            let m = cur.module();
            self.defs.entry(m).or_default().insert(name.into());
        }
    }

    fn name(&mut self, file: &str, cur: &Cursor, path: Vec<String>) {
        if !cur.in_test() {
            let module = cur.module();
            self.refs.push(Ref {
                file: file.into(),
                module,
                path,
            });
        }
    }

    /// A `use` declaration: its paths are references, and at module level
    /// its names are the module's.
    fn use_decl(&mut self, file: &str, cur: &Cursor, tree: &[String]) {
        let m = cur.module();
        for (mut path, name) in use_paths(tree) {
            if path.last().is_some_and(|l| l == "self") {
                path.pop(); // `a::b::{self}` is `a::b`
            }
            let name = match name.as_deref() {
                Some("self") => path.last().cloned(),
                n => n.map(String::from),
            };
            if cur.at_item_level() {
                match name {
                    None => {
                        let glob = path[..path.len() - 1].to_vec();
                        self.globs.entry(m.clone()).or_default().push(glob);
                    }
                    Some(n) if n != "_" => {
                        let uses = self.uses.entry(m.clone()).or_default();
                        uses.insert(n, path.clone());
                    }
                    Some(_) => {}
                }
            }
            self.name(file, cur, path);
        }
    }

    /// Reads one file's tokens at module `base`.
    fn scan(&mut self, file: &str, base: ModPath, toks: &[String]) {
        let mut cur = Cursor {
            base,
            depth: 0,
            inline: vec![],
            test_at: None,
            pending_test: false,
        };
        let tok = |k: usize| toks.get(k).map_or("", String::as_str);
        let word = |k: usize| tok(k).starts_with(|c: char| c.is_alphabetic() || c == '_');
        let mut i = 0;
        while i < toks.len() {
            let t = tok(i);
            if t == "#"
                && (1..7)
                    .map(|k| tok(i + k))
                    .eq(["[", "cfg", "(", "test", ")", "]"])
            {
                cur.pending_test = true;
                i += 7;
                continue;
            }
            match t {
                "{" => cur.open(),
                "}" => cur.close(),
                ";" => cur.pending_test = false,
                "mod" if word(i + 1) && tok(i + 2) == "{" => {
                    self.define(&cur, tok(i + 1));
                    cur.inline.push((cur.depth, tok(i + 1).into()));
                    let m = cur.module();
                    self.modules.insert(m, file.into());
                    i += 2;
                    continue;
                }
                "mod" if word(i + 1) && tok(i + 2) == ";" => {
                    self.define(&cur, tok(i + 1));
                    if cur.in_test() {
                        let mut m = cur.module();
                        m.push(tok(i + 1).into());
                        self.test_modules.insert(m);
                    }
                }
                "macro_rules" if tok(i + 1) == "!" => {
                    self.macros.insert(tok(i + 2).into(), file.into());
                }
                "use" => {
                    let end = (i..toks.len())
                        .find(|&k| toks[k] == ";")
                        .unwrap_or(toks.len());
                    self.use_decl(file, &cur, &toks[i + 1..end]);
                    cur.pending_test = false;
                    i = end + 1;
                    continue;
                }
                _ if ITEM_KEYWORDS.contains(&t) && word(i + 1) => self.define(&cur, tok(i + 1)),
                // A path, unless it continues one or names a visibility.
                _ if word(i)
                    && tok(i + 1) == "::"
                    && !["::", "in"].contains(&tok(i.wrapping_sub(1))) =>
                {
                    let mut path = vec![t.to_string()];
                    let mut j = i + 1;
                    while tok(j) == "::" && word(j + 1) {
                        path.push(tok(j + 1).into());
                        j += 2;
                    }
                    self.name(file, &cur, path);
                    i = j;
                    continue;
                }
                _ => {}
            }
            i += 1;
        }
    }
}

// ---------------------------------------------------------------- resolving

impl Facts {
    /// `path` as named in `module`, from the crate's root; `None` when it
    /// leaves the crate (another crate, `std`, a local name).
    fn absolute(&self, module: &[String], path: &[String]) -> Option<ModPath> {
        let first = path.first()?.as_str();
        if first == "crate" {
            return Some(path[1..].to_vec());
        }
        if first == "super" || first == "self" {
            let mut cur = module.to_vec();
            let steps = path.iter().take_while(|s| *s == "super" || *s == "self");
            for s in steps.clone() {
                if s == "super" {
                    cur.pop();
                }
            }
            cur.extend(path[steps.count()..].iter().cloned());
            return Some(cur);
        }
        let mut child = module.to_vec();
        child.push(first.into());
        if self.modules.contains_key(&child) {
            child.extend(path[1..].iter().cloned());
            return Some(child);
        }
        let alias = self.uses.get(module)?.get(first)?;
        if alias.first().is_some_and(|a| a == first) {
            return None; // a crate of that name (`use rayon;`)
        }
        let mut whole = self.absolute(module, alias)?;
        whole.extend(path[1..].iter().cloned());
        Some(whole)
    }

    /// The module that defines the item named by the absolute `segs`,
    /// through re-exports and internal globs.
    fn resolve(&self, segs: &[String], seen: &mut BTreeSet<(ModPath, String)>) -> ModPath {
        let mut m: ModPath = vec![];
        let mut k = 0;
        while k < segs.len() {
            let mut next = m.clone();
            next.push(segs[k].clone());
            if !self.modules.contains_key(&next) {
                break;
            }
            m = next;
            k += 1;
        }
        let Some(name) = segs.get(k) else {
            return m;
        };
        if self.defs.get(&m).is_some_and(|d| d.contains(name))
            || !seen.insert((m.clone(), name.clone()))
        {
            return m;
        }
        if let Some(path) = self.uses.get(&m).and_then(|u| u.get(name)) {
            return match self.absolute(&m, path) {
                Some(mut target) => {
                    target.extend(segs[k + 1..].iter().cloned());
                    self.resolve(&target, seen)
                }
                None => m,
            };
        }
        for glob in self.globs.get(&m).into_iter().flatten() {
            if let Some(mut target) = self.absolute(&m, glob) {
                target.extend(segs[k..].iter().cloned());
                let r = self.resolve(&target, seen);
                if self.defs.get(&r).is_some_and(|d| d.contains(name)) {
                    return r;
                }
            }
        }
        m
    }

    fn is_test(&self, module: &[String]) -> bool {
        (0..=module.len()).any(|n| self.test_modules.contains(&module[..n]))
    }

    /// The file → file graph of the references outside test code.
    fn graph(&self) -> Graph {
        let mut g = Graph::new();
        for file in self.modules.values() {
            g.entry(file.clone()).or_default();
        }
        for r in self.refs.iter().filter(|r| !self.is_test(&r.module)) {
            let Some(to) = self.file_of(r) else {
                continue;
            };
            if !to.starts_with(&file_module(&r.file)) {
                let to = self.modules[&to].clone();
                g.entry(r.file.clone()).or_default().insert(to);
            }
        }
        g
    }

    /// The module (with a file) that defines what `r` names.
    fn file_of(&self, r: &Ref) -> Option<ModPath> {
        let mut segs = self.absolute(&r.module, &r.path)?;
        if segs.last().is_some_and(|s| s == "*") {
            segs.pop();
        }
        if let [name] = segs.as_slice()
            && let Some(file) = self.macros.get(name)
        {
            return Some(file_module(file));
        }
        let target = self.resolve(&segs, &mut BTreeSet::new());
        self.modules.contains_key(&target).then_some(target)
    }
}

/// The graph of a crate given as `(path relative to src/, text)` pairs; a
/// binary root (`main.rs`, `bin/`) beside a `lib.rs` is another crate.
fn crate_graph(files: &[(String, String)]) -> Graph {
    let mut facts = Facts::default();
    let lib: Vec<&(String, String)> = files
        .iter()
        .filter(|(rel, _)| rel != "main.rs" && !rel.starts_with("bin/"))
        .collect();
    for (rel, _) in &lib {
        facts.modules.insert(file_module(rel), rel.clone());
    }
    for (rel, text) in &lib {
        facts.scan(rel, file_module(rel), &tokens(&strip(text)));
    }
    facts.graph()
}

/// The strongly connected components of more than one file (Tarjan).
fn cycles(g: &Graph) -> Vec<Vec<String>> {
    struct Tarjan<'a> {
        g: &'a Graph,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        out: Vec<Vec<String>>,
    }
    impl<'a> Tarjan<'a> {
        fn visit(&mut self, v: &'a str) {
            let i = self.index.len();
            self.index.insert(v, i);
            self.low.insert(v, i);
            self.stack.push(v);
            let g = self.g;
            for w in g.get(v).into_iter().flatten() {
                if !self.index.contains_key(w.as_str()) {
                    self.visit(w);
                    let lw = self.low[w.as_str()];
                    self.low.entry(v).and_modify(|l| *l = (*l).min(lw));
                } else if self.stack.contains(&w.as_str()) {
                    let iw = self.index[w.as_str()];
                    self.low.entry(v).and_modify(|l| *l = (*l).min(iw));
                }
            }
            if self.low[v] == self.index[v] {
                let at = self
                    .stack
                    .iter()
                    .rposition(|&x| x == v)
                    .expect("on the stack");
                let mut comp: Vec<String> = self.stack.drain(at..).map(String::from).collect();
                comp.sort();
                if comp.len() > 1 {
                    self.out.push(comp);
                }
            }
        }
    }
    let mut t = Tarjan {
        g,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: vec![],
        out: vec![],
    };
    for v in g.keys() {
        if !t.index.contains_key(v.as_str()) {
            t.visit(v);
        }
    }
    t.out
}

// ---------------------------------------------------------------- the tests

fn rust_files(dir: &Path, root: &Path, out: &mut Vec<(String, String)>) {
    for entry in std::fs::read_dir(dir).expect("readable source folder") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let rel = path.strip_prefix(root).expect("below src");
            let rel = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/");
            out.push((
                rel,
                std::fs::read_to_string(&path).expect("readable source"),
            ));
        }
    }
}

fn workspace_graph(krate: &str) -> Graph {
    let src = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(krate)
        .join("src");
    let mut files = vec![];
    rust_files(&src, &src, &mut files);
    crate_graph(&files)
}

fn edge_count(g: &Graph) -> usize {
    g.values().map(BTreeSet::len).sum()
}

/// Each circle as `a <-> b (a -> b, b -> a)`, with the edges inside it.
fn describe(g: &Graph, circles: &[Vec<String>]) -> Vec<String> {
    circles
        .iter()
        .map(|c| {
            let inner: Vec<String> = c
                .iter()
                .flat_map(|a| {
                    g[a].iter()
                        .filter(|b| c.contains(*b))
                        .map(move |b| format!("{a} -> {b}"))
                })
                .collect();
            format!("{} ({})", c.join(" <-> "), inner.join(", "))
        })
        .collect()
}

#[test]
fn no_crate_of_the_workspace_has_an_import_circle() {
    let found: Vec<String> = ["core", "verify", "reports", "python", "benches"]
        .iter()
        .flat_map(|krate| {
            let g = workspace_graph(krate);
            describe(&g, &cycles(&g))
                .into_iter()
                .map(move |c| format!("{krate}/src: {c}"))
        })
        .collect();
    assert!(found.is_empty(), "import circles: {found:#?}");
}

#[test]
fn the_graph_holds_the_imports_the_crates_are_known_to_make() {
    let core = workspace_graph("core");
    let verify = workspace_graph("verify");
    let reports = workspace_graph("reports");
    for (name, g) in [("core", &core), ("verify", &verify), ("reports", &reports)] {
        assert!(
            g.len() >= 40 && edge_count(g) >= g.len(),
            "{name}: {} files, {} edges: the scan lost the imports",
            g.len(),
            edge_count(g)
        );
    }
    let has = |g: &Graph, a: &str, b: &str| g.get(a).is_some_and(|s| s.contains(b));
    // `use super::stash::Stash;`
    assert!(has(&core, "ndimage/nd_prefilter.rs", "ndimage/stash.rs"));
    // `use super::{Interpolant, PointRule, …}`: PointRule re-exported by
    // interpolant.rs, defined in point_rule.rs.
    assert!(has(
        &core,
        "ndimage/interpolant/batch.rs",
        "ndimage/interpolant/point_rule.rs"
    ));
    // `crate::interrupt::register(&tmp)` in a function body.
    assert!(has(&reports, "output.rs", "interrupt.rs"));
    // A `pub use` of another module's items is an import …
    assert!(has(
        &verify,
        "check/prefilter.rs",
        "check/interpolation_conditions.rs"
    ));
    // … a parent's `pub use` of its children is not.
    assert!(!has(
        &verify,
        "check/mod.rs",
        "check/interpolation_conditions.rs"
    ));
}

fn fixture(files: &[(&str, &str)]) -> Vec<(String, String)> {
    files
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

#[test]
fn a_circle_behind_a_re_export_is_found_and_test_code_is_not_one() {
    let lib = "pub mod a;\npub mod b;\npub use a::Thing;\n";
    let a = "use crate::b::helper;\npub struct Thing;\npub fn f() { helper() }\n";
    // b names a's `Thing` only through the root's re-export.
    let b = "pub fn helper() {}\npub fn g() -> crate::Thing { crate::Thing }\n";
    let g = crate_graph(&fixture(&[("lib.rs", lib), ("a.rs", a), ("b.rs", b)]));
    assert_eq!(
        cycles(&g),
        vec![vec!["a.rs".to_string(), "b.rs".to_string()]]
    );
    // The same reference only in a test module, a comment or a string.
    let b_test = "pub fn helper() {}\n#[cfg(test)]\nmod tests {\n    use crate::Thing;\n}\n\
                  // crate::Thing\nconst S: &str = \"crate::Thing\";\n";
    let g = crate_graph(&fixture(&[("lib.rs", lib), ("a.rs", a), ("b.rs", b_test)]));
    assert!(cycles(&g).is_empty(), "{g:?}");
    assert!(g["a.rs"].contains("b.rs"));
}
