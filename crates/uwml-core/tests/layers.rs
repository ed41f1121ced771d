//! The core's modules import one way: the graph of `crate::` paths between the files of `src/`
//! has no cycle (no module imports one that imports it back, directly or through others), and the
//! joint losses depend on nothing but the errors and the checks. Read from the sources, with std.
#![allow(missing_docs, clippy::unwrap_used, clippy::indexing_slicing, clippy::expect_used)]

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Module name -> the modules its code names through `crate::` (comments left out).
type Graph = BTreeMap<String, BTreeSet<String>>;

/// The modules that `code` names as `crate::module` or inside `crate::{module::.., module2}`.
fn named_modules(code: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        rest = &rest[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // The first name of each item at the group's top level.
            let (mut depth, mut item_start) = (0usize, true);
            let mut word = String::new();
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => item_start = true,
                    c if (c.is_alphanumeric() || c == '_') && item_start => word.push(c),
                    _ => {
                        if !word.is_empty() {
                            names.insert(std::mem::take(&mut word));
                            item_start = false;
                        }
                    }
                }
            }
            if !word.is_empty() {
                names.insert(word);
            }
        } else {
            let word: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            names.insert(word);
        }
    }
    names
}

/// The graph of the core's modules, from `src/*.rs` (comments stripped), edges to modules only.
fn core_graph() -> Graph {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = BTreeMap::new();
    for entry in std::fs::read_dir(&src).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "rs") {
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            let code: String = std::fs::read_to_string(&path)
                .unwrap()
                .lines()
                .map(|line| line.split("//").next().unwrap_or(""))
                .collect::<Vec<_>>()
                .join("\n");
            files.insert(name, code);
        }
    }
    assert!(files.len() > 20 && files.contains_key("model") && files.contains_key("hydro"), "{:?}", files.keys());
    let modules: BTreeSet<String> = files.keys().filter(|name| *name != "lib").cloned().collect();
    files
        .iter()
        .filter(|(name, _)| *name != "lib")
        .map(|(name, code)| {
            let edges = named_modules(code).into_iter().filter(|m| modules.contains(m) && m != name).collect();
            (name.clone(), edges)
        })
        .collect()
}

/// A cycle of `graph`, as the modules along it (the first repeated at the end), if it has one.
fn find_cycle(graph: &Graph) -> Option<Vec<String>> {
    // Depth-first, with the path on the stack: an edge back into the path closes a cycle.
    fn visit(graph: &Graph, node: &str, path: &mut Vec<String>, done: &mut BTreeSet<String>) -> Option<Vec<String>> {
        if let Some(start) = path.iter().position(|n| n == node) {
            let mut cycle = path[start..].to_vec();
            cycle.push(node.to_string());
            return Some(cycle);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            if let Some(cycle) = visit(graph, next, path, done) {
                return Some(cycle);
            }
        }
        path.pop();
        done.insert(node.to_string());
        None
    }
    let mut done = BTreeSet::new();
    graph.keys().find_map(|node| visit(graph, node, &mut Vec::new(), &mut done))
}

#[test]
fn no_module_imports_one_that_imports_it_back() {
    let graph = core_graph();
    let cycle = find_cycle(&graph);
    assert!(cycle.is_none(), "an import cycle in uwml-core: {}", cycle.unwrap_or_default().join(" -> "));
}

#[test]
fn the_losses_depend_on_nothing_but_the_errors_and_the_checks() {
    let graph = core_graph();
    let allowed: BTreeSet<String> = ["error", "check"].map(String::from).into();
    assert!(graph["losses"].is_subset(&allowed), "losses imports {:?}", graph["losses"]);
    // The number type knows nothing of the loss model; the description, nothing of the evaluation.
    assert!(!graph["real"].contains("losses"), "{:?}", graph["real"]);
    for module in ["model", "parts", "check", "water", "conditions"] {
        for evaluation in ["hydro", "kinematics", "regressors", "derivatives", "added_mass"] {
            assert!(!graph[module].contains(evaluation), "{module} imports {evaluation}");
        }
    }
}

#[test]
fn the_reader_sees_groups_and_paths_and_the_check_finds_cycles() {
    let names = named_modules("use crate::{a::X, b::{c::Y, Z}, d};\nlet x = crate::e::f();");
    assert_eq!(names, ["a", "b", "d", "e"].map(String::from).into());
    let graph: Graph = [("a", vec!["b"]), ("b", vec!["c"]), ("c", vec!["a"]), ("d", vec![])]
        .into_iter()
        .map(|(n, e)| (n.to_string(), e.into_iter().map(String::from).collect()))
        .collect();
    assert_eq!(find_cycle(&graph).unwrap().len(), 4);
    let mut acyclic = graph.clone();
    acyclic.get_mut("c").unwrap().clear();
    assert_eq!(find_cycle(&acyclic), None);
}
