//! No cycle of imports between the top-level modules of the host or of the core (issue 17):
//! a module that a module imports must not import it back, directly or through others, so
//! the layers of `docs/architecture.md` hold and each module can be read on its own.
//!
//! A module's imports are the `crate::NAME` paths in its files (its `NAME.rs` and everything
//! under `NAME/`), outside comments and outside its `#[cfg(test)]` modules, inline or in a
//! file of their own (a test may use the layers above the code it tests). The check is shown
//! to fail on planted cycles.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Module name → the source text of its files.
type Sources = BTreeMap<String, String>;

/// The top-level modules of the crate whose `src` is `root`, with their sources.
fn read_crate(root: &Path) -> Sources {
    let mut out = Sources::new();
    for entry in std::fs::read_dir(root).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if name == "lib" || name == "main" {
            continue;
        }
        let text = out.entry(name).or_default();
        read_tree(&path, text);
    }
    out
}

/// The modules that `mod.rs` of `dir` declares as `#[cfg(test)] mod NAME;`: test modules in
/// files of their own.
fn test_module_files(dir: &Path) -> BTreeSet<String> {
    let source = std::fs::read_to_string(dir.join("mod.rs")).unwrap_or_default();
    let mut names = BTreeSet::new();
    let mut after_cfg_test = false;
    for line in source.lines().map(str::trim) {
        if after_cfg_test {
            let declared = line.rsplit_once("mod ").map(|(_, r)| r);
            if let Some(name) = declared.and_then(|r| r.strip_suffix(';')) {
                names.insert(format!("{name}.rs"));
            }
        }
        after_cfg_test = line == "#[cfg(test)]";
    }
    names
}

/// Appends the text of `path`, or of every `.rs` file below it that is not a test module.
fn read_tree(path: &Path, text: &mut String) {
    if path.is_dir() {
        let tests = test_module_files(path);
        let mut entries: Vec<_> = std::fs::read_dir(path)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| {
                let name = p.file_name().unwrap_or_default().to_string_lossy();
                !tests.contains(name.as_ref())
            })
            .collect();
        entries.sort();
        for p in entries {
            read_tree(&p, text);
        }
    } else if path.extension().is_some_and(|e| e == "rs") {
        let source = std::fs::read_to_string(path).unwrap();
        // Tests sit at the end of a file; what they import is not the module's.
        let code = source.split("#[cfg(test)]").next().unwrap_or("");
        for line in code.lines() {
            let line = line.split("//").next().unwrap_or("");
            text.push_str(line);
            text.push('\n');
        }
    }
}

/// The modules each module imports (other top-level modules only).
fn imports(sources: &Sources) -> BTreeMap<&str, BTreeSet<&str>> {
    let mut graph = BTreeMap::new();
    for (name, text) in sources {
        let mut used = BTreeSet::new();
        for (at, _) in text.match_indices("crate::") {
            let rest = &text[at + "crate::".len()..];
            let end = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            let target = &rest[..end];
            if target != name.as_str() {
                if let Some((key, _)) = sources.get_key_value(target) {
                    used.insert(key.as_str());
                }
            }
        }
        graph.insert(name.as_str(), used);
    }
    graph
}

/// A cycle of the graph as the modules along it, if there is one.
fn find_cycle<'a>(graph: &BTreeMap<&'a str, BTreeSet<&'a str>>) -> Option<Vec<&'a str>> {
    fn visit<'a>(
        node: &'a str,
        graph: &BTreeMap<&'a str, BTreeSet<&'a str>>,
        path: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) -> Option<Vec<&'a str>> {
        if let Some(start) = path.iter().position(|&n| n == node) {
            let mut cycle = path[start..].to_vec();
            cycle.push(node);
            return Some(cycle);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node);
        for &next in graph.get(node).into_iter().flatten() {
            if let Some(c) = visit(next, graph, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.insert(node);
        None
    }
    let mut done = BTreeSet::new();
    for &node in graph.keys() {
        if let Some(c) = visit(node, graph, &mut Vec::new(), &mut done) {
            return Some(c);
        }
    }
    None
}

#[test]
fn host_and_core_modules_import_without_cycles() {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    for root in [here.join("src"), here.join("../core/src")] {
        let sources = read_crate(&root);
        assert!(sources.len() > 10, "{}: too few modules", root.display());
        let graph = imports(&sources);
        let edges: usize = graph.values().map(BTreeSet::len).sum();
        assert!(
            edges > 10,
            "{}: the import scan found {edges} imports",
            root.display()
        );
        if let Some(cycle) = find_cycle(&graph) {
            panic!("{}: import cycle {}", root.display(), cycle.join(" → "));
        }
    }
}

#[test]
fn planted_cycles_are_found() {
    let sources = |pairs: &[(&str, &str)]| -> Sources {
        pairs
            .iter()
            .map(|(n, t)| (n.to_string(), t.to_string()))
            .collect()
    };
    // world → step → world, through a `use` and an inline path.
    let s = sources(&[
        ("world", "use crate::step::parts;\n"),
        ("step", "fn f() { crate::world::World::new(); }\n"),
        ("num", ""),
    ]);
    let cycle = find_cycle(&imports(&s)).expect("a two-module cycle");
    assert_eq!(cycle.first(), cycle.last());
    assert_eq!(cycle.len(), 3);
    // a → b → c → a.
    let s = sources(&[
        ("a", "use crate::b;"),
        ("b", "use crate::c::X;"),
        ("c", "use crate::a::{Y, Z};"),
    ]);
    assert_eq!(find_cycle(&imports(&s)).map(|c| c.len()), Some(4));
    // A layered graph, and a module naming itself, have none.
    let s = sources(&[
        ("a", "use crate::b; use crate::a::inner;"),
        ("b", "use crate::c;"),
        ("c", ""),
    ]);
    assert_eq!(find_cycle(&imports(&s)), None);
}

#[test]
fn comments_and_tests_do_not_count_as_imports() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("low.rs"),
        "/// See [`crate::high::Thing`].\nfn f() {} // crate::high\n#[cfg(test)]\nmod tests { use crate::high::Thing; }\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("high.rs"), "use crate::low::f;\n").unwrap();
    // A test module in a file of its own (`#[cfg(test)] mod tests;`) counts as a test too;
    // the module's other files still count.
    let mid = dir.path().join("mid");
    std::fs::create_dir(&mid).unwrap();
    std::fs::write(mid.join("mod.rs"), "mod part;\n#[cfg(test)]\nmod tests;\n").unwrap();
    std::fs::write(mid.join("part.rs"), "use crate::low::f;\n").unwrap();
    std::fs::write(mid.join("tests.rs"), "use crate::high::Thing;\n").unwrap();
    let sources = read_crate(dir.path());
    let graph = imports(&sources);
    assert!(graph["low"].is_empty(), "{graph:?}");
    assert_eq!(graph["high"].iter().copied().collect::<Vec<_>>(), ["low"]);
    assert_eq!(graph["mid"].iter().copied().collect::<Vec<_>>(), ["low"]);
}
