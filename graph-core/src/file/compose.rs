//! Parts: passes and resources written once in a part file and used by graphs, each use
//! under names of its own. Loading writes every use out into the graph here, so that the
//! rest of loading, the plan, `explain` and specialisation see the graph as if its file
//! had been written that way; each pass remembers the uses it came from.
//!
//! Inside a use, a name the part takes or gives is the name the use binds to it (a taken
//! one the use leaves unbound: the same name, around the use); any other name (the
//! part's passes, its own resources, the versions they write and what it gives unbound)
//! gets the use's `prefix`. A use's `when` joins the conditions of everything in it, and
//! its `values` replace the part's uses of those parameters in its text.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use typed_arena::Arena;

use super::conditions::column_of;
use super::error::{ErrorKind, FileError, FileErrors, Location};
use super::pairs::Pairs;
use super::param_uses;
use super::params::GraphParams;
use super::references::{ReferenceError, References};
use super::schema::{
    self, Entry, FileKind, GraphFile, GraphText, Interface, Name, PartFile, PassDecl, ResourceDecl,
    Used,
};
use super::shown::Shown;
use super::source::Source;
use crate::bounded_read;
use crate::condition::{Condition, Features};

/// The most passes and part uses parts may add to one graph: parts that use parts several
/// times each multiply, so a few small files could otherwise ask for billions.
const MAX_ENTRIES: usize = 100_000;

/// Writes out the parts a graph uses. Part files are read into `arena`, so that names
/// borrowed from them live as long as the graph's own.
pub(super) struct Composer<'a, 'r> {
    arena: &'a Arena<(PathBuf, String)>,
    references: &'r References,
    /// The graph's declared features, which every part's must be among.
    features: Features,
    /// Part files on the way to the one being written out, with where each is used, to
    /// refuse a cycle.
    stack: Vec<(PathBuf, Location)>,
    /// (part file, prefix) of each use so far -> where the use is.
    instances: HashMap<(PathBuf, String), Location>,
    /// Passes and uses written out of parts so far.
    entries: usize,
    /// What uses bind to what their parts take, checked once the graph is whole.
    bindings: Vec<Binding<'a>>,
    /// Taken slots bound by name: (part, slot, the name in the graph, where the use is).
    by_name: Vec<(String, Name<'a>, Name<'a>, Location)>,
    /// Every error found, reported by [`finish`](Self::finish); a preset's join them.
    pub errors: Vec<FileError>,
}

/// The names of one use's inside in the graph: see the module's documentation.
#[derive(Clone, Default)]
struct Instance<'a> {
    prefix: String,
    /// Slot of the part's interface -> the name in the graph the use binds to it.
    bound: HashMap<String, Name<'a>>,
    /// The conditions of the uses around, joined.
    when: Option<Name<'a>>,
    used: Vec<Used>,
}

impl<'a> Instance<'a> {
    /// A name of the part's inside: bound, or under the prefix.
    fn name(&self, name: &Name<'a>) -> Name<'a> {
        match self.bound.get(name.as_str()) {
            Some(bound) => Name::made_from(bound.as_str().to_owned(), name, 0),
            None => self.prefixed(name),
        }
    }

    /// A pass's name, or a name no binding reaches.
    fn prefixed(&self, name: &Name<'a>) -> Name<'a> {
        match self.prefix.is_empty() {
            true => name.clone(),
            false => Name::made_from(
                format!("{}{}", self.prefix, name.as_str()),
                name,
                self.prefix.chars().count(),
            ),
        }
    }

    /// `own` condition joined to the uses' around it.
    fn when(&self, own: Option<&Name<'a>>) -> Option<Name<'a>> {
        match (&self.when, own) {
            (None, own) => own.cloned(),
            (Some(outer), None) => Some(outer.clone()),
            (Some(outer), Some(own)) => Some(Name::made_from(
                format!("{} & {}", outer.as_str(), own.as_str()),
                own,
                outer.as_str().chars().count() + 3,
            )),
        }
    }
}

/// A slot's interface and the name its use gives it in the graph.
struct Binding<'a> {
    part: String,
    /// "takes" or "gives".
    side: &'static str,
    slot: Name<'a>,
    interface: Interface<'a>,
    bound: Name<'a>,
    /// Where the use binds it.
    at: Name<'a>,
}

impl<'a, 'r> Composer<'a, 'r> {
    pub fn new(
        arena: &'a Arena<(PathBuf, String)>,
        references: &'r References,
        features: &[Name<'a>],
    ) -> Self {
        Composer {
            arena,
            references,
            features: features.iter().map(|f| f.as_str().to_owned()).collect(),
            stack: Vec::new(),
            instances: HashMap::new(),
            entries: 0,
            bindings: Vec::new(),
            by_name: Vec::new(),
            errors: Vec::new(),
        }
    }

    /// The graph file `graph` with its parts written out.
    pub fn graph(&mut self, source: &mut Source<'a>, graph: GraphText<'a>) -> GraphFile<'a> {
        let mut file = GraphFile {
            features: graph.features,
            resources: graph.resources,
            passes: Vec::new(),
            outputs: graph.outputs,
        };
        self.entries(source, graph.passes, &Instance::default(), &mut file);
        file
    }

    /// The graph that checks a part on its own: the part used once, what it takes bound to
    /// imported placeholders of its interface (`Any`: an `rgba16float` texture), what it
    /// gives and does not declare itself declared as its interface says (`Any`: left to
    /// be a version of what it takes), every feature it names declared, and what it gives
    /// kept as outputs.
    pub fn part_alone(
        &mut self,
        source: &mut Source<'a>,
        path: &Path,
        part: PartFile<'a>,
    ) -> GraphFile<'a> {
        let mut file = GraphFile {
            features: part.features.clone(),
            resources: Pairs::default(),
            passes: Vec::new(),
            outputs: part.gives.0.iter().map(|(slot, _)| slot.clone()).collect(),
        };
        for (slot, interface) in &part.takes.0 {
            file.resources
                .0
                .push((slot.clone(), interface.placeholder(true)));
        }
        let own = |slot: &Name<'_>| {
            part.resources
                .0
                .iter()
                .any(|(n, _)| n.as_str() == slot.as_str())
        };
        for (slot, interface) in &part.gives.0 {
            if !own(slot) && !matches!(interface, Interface::Any) {
                file.resources
                    .0
                    .push((slot.clone(), interface.placeholder(false)));
            }
        }
        let bound = |side: &Pairs<Name<'a>, Interface<'a>>| {
            Pairs(
                side.0
                    .iter()
                    .map(|(slot, _)| (slot.clone(), slot.clone()))
                    .collect(),
            )
        };
        let entry = Entry {
            name: None,
            plugin: None,
            part: None,
            prefix: None,
            when: None,
            params: None,
            values: Pairs::default(),
            inputs: bound(&part.takes),
            outputs: bound(&part.gives),
            optional: Vec::new(),
        };
        let used = Used {
            part: path.display().to_string(),
            at: source.location(crate::position::Position::START),
        };
        let top = Instance::default();
        self.instance(
            source,
            part,
            used,
            &entry,
            &top,
            // The part is the file checked: its passes are the file's own, from no use.
            (String::new(), None, Vec::new()),
            &mut file,
        );
        file
    }

    /// Passes and part uses a preset adds, written out as the graph's own.
    pub fn added(&mut self, source: &mut Source<'a>, entries: Vec<Entry<'a>>) -> GraphFile<'a> {
        let mut file = GraphFile {
            features: Vec::new(),
            resources: Pairs::default(),
            passes: Vec::new(),
            outputs: Vec::new(),
        };
        self.entries(source, entries, &Instance::default(), &mut file);
        file
    }

    /// Checks the uses' bindings in the whole `file`. A graph whose parts could not all be
    /// written out is an error; otherwise the bindings' errors are returned, to be reported
    /// with what loading finds next (a wrong format also upsets the plugin reading it).
    pub fn finish(
        mut self,
        source: &Source<'a>,
        file: &GraphFile<'a>,
    ) -> Result<Vec<FileError>, FileErrors> {
        if !self.errors.is_empty() {
            return Err(FileErrors::sorted(self.errors));
        }
        self.check_bindings(source, file);
        Ok(self.errors)
    }

    /// Writes out `entries`, inside `instance`, into `file`.
    fn entries(
        &mut self,
        source: &mut Source<'a>,
        entries: Vec<Entry<'a>>,
        instance: &Instance<'a>,
        file: &mut GraphFile<'a>,
    ) {
        for entry in entries {
            // The graph's own file is bounded by its size; parts' uses multiply.
            self.entries += usize::from(!instance.used.is_empty());
            if self.entries > MAX_ENTRIES {
                self.errors.push(FileError {
                    location: entry_location(source, &entry),
                    kind: ErrorKind::TooManyEntries { limit: MAX_ENTRIES },
                });
                return;
            }
            match &entry.part {
                Some(_) => self.use_part(source, entry, instance, file),
                None => self.pass(source, entry, instance, file),
            }
        }
    }

    /// A pass entry, its names and condition those of `instance`.
    fn pass(
        &mut self,
        source: &Source<'a>,
        entry: Entry<'a>,
        instance: &Instance<'a>,
        file: &mut GraphFile<'a>,
    ) {
        let (Some(name), Some(plugin)) = (&entry.name, &entry.plugin) else {
            self.errors.push(FileError {
                location: entry_location(source, &entry),
                kind: ErrorKind::EntryShape {
                    message: "a pass needs a `name` and a `plugin`; a use of a part needs a \
                              `part`"
                        .into(),
                },
            });
            return;
        };
        if let Some((value, _)) = entry.values.0.first() {
            self.errors.push(source.error(
                value,
                ErrorKind::EntryShape {
                    message: format!(
                        "pass \"{}\" has `values`, which only a use of a part has (a pass's \
                         parameters are its `params`)",
                        name.as_str()
                    ),
                },
            ));
        }
        if let Some(prefix) = &entry.prefix {
            self.errors.push(source.error(
                prefix,
                ErrorKind::EntryShape {
                    message: format!(
                        "pass \"{}\" has a `prefix`, which only a use of a part has",
                        name.as_str()
                    ),
                },
            ));
        }
        let names = |pairs: &Pairs<Name<'a>, Name<'a>>| {
            Pairs(
                pairs
                    .0
                    .iter()
                    .map(|(slot, name)| (slot.clone(), instance.name(name)))
                    .collect(),
            )
        };
        file.passes.push(PassDecl {
            name: instance.prefixed(name),
            plugin: plugin.clone(),
            when: instance.when(entry.when.as_ref()),
            inputs: names(&entry.inputs),
            outputs: names(&entry.outputs),
            optional: entry.optional,
            params: entry.params,
            used: instance.used.clone(),
        });
    }

    /// A use of a part: read the part, check the use against its interface, write it out.
    fn use_part(
        &mut self,
        source: &mut Source<'a>,
        entry: Entry<'a>,
        outer: &Instance<'a>,
        file: &mut GraphFile<'a>,
    ) {
        let Some(reference) = entry.part.clone() else {
            return;
        };
        for (field, name) in [("name", &entry.name), ("plugin", &entry.plugin)] {
            if let Some(name) = name {
                self.errors.push(source.error(
                    name,
                    ErrorKind::EntryShape {
                        message: format!(
                            "a use of a part has no `{field}`: its passes are the part's, \
                             named under the use's `prefix`"
                        ),
                    },
                ));
            }
        }
        if entry.params.is_some() {
            self.errors.push(
                source.error(
                    &reference,
                    ErrorKind::EntryShape {
                        message: "a use of a part has no `params`: its passes' parameters are \
                              written in the part"
                            .into(),
                    },
                ),
            );
        }
        if let Some(slot) = entry.optional.first() {
            self.errors.push(
                source.error(
                    slot,
                    ErrorKind::EntryShape {
                        message: "a use of a part has no `optional`: which reads are optional is \
                              written at the part's passes"
                            .into(),
                    },
                ),
            );
        }
        let Some((path, text)) = self.read(source, &reference, &entry.values) else {
            return;
        };
        let part = match schema::kind(text) {
            FileKind::Part => schema::parse_part(text),
            kind => {
                self.errors.push(source.error(
                    &reference,
                    ErrorKind::NotAPart {
                        part: path.display().to_string(),
                        kind: match kind {
                            FileKind::Preset => "a preset",
                            _ => "a graph file",
                        },
                    },
                ));
                return;
            }
        };
        let part = match part {
            Ok(part) => part,
            Err(e) => {
                self.errors.push(Source::new(path, text).syntax(&e));
                return;
            }
        };
        if let Some(cycle) = self.stack.iter().position(|(p, _)| p == path) {
            let chain: Vec<String> = self.stack[cycle..]
                .iter()
                .map(|(p, _)| p.display().to_string())
                .chain([path.display().to_string()])
                .collect();
            self.errors.push(source.error(
                &reference,
                ErrorKind::PartCycle {
                    chain: chain.join(" uses "),
                    first: self.stack[cycle].1.clone(),
                },
            ));
            return;
        }
        let prefix = format!(
            "{}{}",
            outer.prefix,
            entry.prefix.as_ref().map_or("", Name::as_str)
        );
        let at = source.locate(&reference);
        let key = (path.to_path_buf(), prefix.clone());
        if let Some(first) = self.instances.get(&key) {
            self.errors.push(FileError {
                location: at,
                kind: ErrorKind::PartTwice {
                    part: path.display().to_string(),
                    prefix,
                    first: first.clone(),
                },
            });
            return;
        }
        self.instances.insert(key, at.clone());
        self.features(source, &reference, path, &part);
        if let Some(when) = &entry.when {
            if !self.use_condition(source, when, path) {
                return;
            }
        }
        let used = Used {
            part: path.display().to_string(),
            at,
        };
        let when = outer.when(entry.when.as_ref());
        let uses = outer.used.iter().cloned().chain([used.clone()]).collect();
        self.stack.push((path.to_path_buf(), used.at.clone()));
        self.instance(
            source,
            part,
            used,
            &entry,
            outer,
            (prefix, when, uses),
            file,
        );
        self.stack.pop();
    }

    /// Reads the part file `reference` names, from the folder of the file it is written in,
    /// with the parameters `values` names at those values (the text keeps its layout, so
    /// positions in it stay the file's); its text joins `source`.
    fn read(
        &mut self,
        source: &mut Source<'a>,
        reference: &Name<'a>,
        values: &Pairs<Name<'a>, u32>,
    ) -> Option<(&'a Path, &'a str)> {
        let max = bounded_read::MAX_GRAPH_FILE_BYTES;
        let named = match self
            .references
            .read(source.dir_of(reference), reference.as_str(), max)
        {
            Ok(named) => named,
            Err(e) => {
                let reason = match e {
                    ReferenceError::Refused(reason) => reason,
                    ReferenceError::Unreadable { path, reason } => {
                        format!("({}) cannot be read: {reason}", path.display())
                    }
                };
                self.errors.push(source.error(
                    reference,
                    ErrorKind::Reference {
                        what: "the part",
                        reference: Shown(reference.as_str()).to_string(),
                        reason,
                    },
                ));
                return None;
            }
        };
        let text = named.text.strip_prefix('\u{feff}').unwrap_or(&named.text);
        let given = values
            .0
            .iter()
            .fold(GraphParams::new(), |given, (name, value)| {
                given.with(name.as_str(), *value)
            });
        let declared = param_uses::names(text);
        for (name, _) in &values.0 {
            if !declared.iter().any(|d| d == name.as_str()) {
                self.errors.push(source.error(
                    name,
                    ErrorKind::PartParam {
                        part: named.path.display().to_string(),
                        name: name.as_str().to_owned(),
                        declared: listed(&declared, "none"),
                    },
                ));
            }
        }
        let text = param_uses::substitute_given(text, &given);
        let (path, text) = self.arena.alloc((named.path, text));
        source.add(path, text);
        Some((path, text))
    }

    /// Checks a use's own condition, before it is joined to those inside the part (where
    /// an error in it would be placed in the part): it parses, and names only features the
    /// graph declares. Whether it did.
    fn use_condition(&mut self, source: &Source<'a>, when: &Name<'a>, path: &Path) -> bool {
        let part = path.display().to_string();
        let condition = match Condition::parse(when.as_str()) {
            Ok(condition) => condition,
            Err(error) => {
                self.errors.push(FileError {
                    location: source.locate_in(when, error.column()),
                    kind: ErrorKind::BadCondition {
                        owner: format!("the use of part {part}"),
                        condition: when.as_str().to_owned(),
                        error,
                    },
                });
                return false;
            }
        };
        let mut known = true;
        for feature in condition.features().filter(|f| !self.features.contains(f)) {
            known = false;
            let column = column_of(when.as_str(), feature);
            self.errors.push(FileError {
                location: source.locate_in(when, column),
                kind: ErrorKind::UseFeature {
                    part: part.clone(),
                    feature: feature.to_owned(),
                    declared: self.features.to_string(),
                },
            });
        }
        known
    }

    /// Checks that the graph declares every feature the part names.
    fn features(
        &mut self,
        source: &Source<'a>,
        reference: &Name<'a>,
        path: &Path,
        part: &PartFile<'a>,
    ) {
        for feature in &part.features {
            if !self.features.contains(feature.as_str()) {
                self.errors.push(source.error(
                    reference,
                    ErrorKind::PartFeature {
                        part: path.display().to_string(),
                        feature: feature.as_str().to_owned(),
                        at: source.locate(feature),
                        declared: self.features.to_string(),
                    },
                ));
            }
        }
    }

    /// Writes out one use of `part` (`used` names it in messages), whose bindings are
    /// `entry`'s inputs and outputs (names of `outer`'s), its other names under `prefix`,
    /// its conditions joined to `when` and its passes coming from `uses`.
    #[allow(clippy::too_many_arguments)]
    fn instance(
        &mut self,
        source: &mut Source<'a>,
        part: PartFile<'a>,
        used: Used,
        entry: &Entry<'a>,
        outer: &Instance<'a>,
        (prefix, when, uses): (String, Option<Name<'a>>, Vec<Used>),
        file: &mut GraphFile<'a>,
    ) {
        let Used { part: name, at } = used;
        let mut inner = Instance {
            prefix,
            bound: HashMap::new(),
            when,
            used: uses,
        };
        for (side, bindings, interface) in [
            ("takes", &entry.inputs, &part.takes),
            ("gives", &entry.outputs, &part.gives),
        ] {
            for (slot, bound) in &bindings.0 {
                if !interface.0.iter().any(|(s, _)| s.as_str() == slot.as_str()) {
                    let known: Vec<&str> = interface.0.iter().map(|(s, _)| s.as_str()).collect();
                    self.errors.push(source.error(
                        slot,
                        ErrorKind::PartNoSlot {
                            part: name.clone(),
                            side,
                            slot: slot.as_str().to_owned(),
                            known: listed(&known, "nothing"),
                        },
                    ));
                    continue;
                }
                let bound_name = outer.name(bound);
                inner.bound.insert(slot.as_str().to_owned(), bound_name);
            }
        }
        // A taken slot the use leaves unbound is bound to the name it has in the part, in
        // the scope of the use; the graph must have it (checked once the graph is whole).
        for (slot, _) in &part.takes.0 {
            if !inner.bound.contains_key(slot.as_str()) {
                let bound = outer.name(slot);
                self.by_name
                    .push((name.clone(), slot.clone(), bound.clone(), at.clone()));
                inner.bound.insert(slot.as_str().to_owned(), bound);
            }
        }
        // What the interface says of each slot, checked once the graph is whole: taken
        // slots hold what the use binds, given ones what the part writes under the name.
        let sides = [("takes", &part.takes), ("gives", &part.gives)];
        for (side, slot, interface) in sides
            .into_iter()
            .flat_map(|(side, slots)| slots.0.iter().map(move |(s, i)| (side, s, i)))
        {
            if !matches!(interface, Interface::Any) {
                self.bindings.push(Binding {
                    part: name.clone(),
                    side,
                    slot: slot.clone(),
                    interface: interface.clone(),
                    bound: inner.name(slot),
                    at: [&entry.inputs, &entry.outputs]
                        .into_iter()
                        .flat_map(|pairs| &pairs.0)
                        .find(|(s, _)| s.as_str() == slot.as_str())
                        .map_or_else(|| slot.clone(), |(_, bound)| bound.clone()),
                });
            }
        }
        for (name, mut decl) in part.resources.0 {
            decl.set_when(inner.when(decl.when()));
            if let Some(of) = decl.history_of_mut() {
                *of = inner.name(of);
            }
            file.resources.0.push((inner.name(&name), decl));
        }
        self.entries(source, part.passes, &inner, file);
    }

    /// Checks each use's bindings against what its part takes, in the whole `file`.
    fn check_bindings(&mut self, source: &Source<'a>, file: &GraphFile<'a>) {
        for (part, slot, bound, at) in std::mem::take(&mut self.by_name) {
            if declaration(file, bound.as_str()).is_none() {
                self.errors.push(FileError {
                    location: at,
                    kind: ErrorKind::PartUnbound {
                        part,
                        slot: bound.as_str().to_owned(),
                        at: source.locate(&slot),
                    },
                });
            }
        }
        for binding in std::mem::take(&mut self.bindings) {
            let Some(found) = declaration(file, binding.bound.as_str()) else {
                // Not declared anywhere: resolving names reports it.
                continue;
            };
            if let Some(found) = binding.interface.mismatch(found) {
                self.errors.push(source.error(
                    &binding.at,
                    ErrorKind::PartBinding {
                        part: binding.part,
                        side: binding.side,
                        slot: binding.slot.as_str().to_owned(),
                        wanted: binding.interface.shown(),
                        at: source.locate(&binding.slot),
                        bound: binding.bound.as_str().to_owned(),
                        found,
                    },
                ));
            }
        }
    }
}

/// The declared resource whose version `name` is: declared under that name, or written by
/// a pass that modifies what it reads through the same slot.
fn declaration<'f, 'a>(file: &'f GraphFile<'a>, name: &str) -> Option<&'f ResourceDecl<'a>> {
    let mut name = name;
    // Each step goes one pass back; more steps than passes is a cycle, which ordering
    // reports.
    for _ in 0..=file.passes.len() {
        if let Some((_, decl)) = file.resources.0.iter().find(|(n, _)| n.as_str() == name) {
            return Some(decl);
        }
        let (pass, slot) = file.passes.iter().find_map(|pass| {
            let (slot, _) = pass.outputs.0.iter().find(|(_, v)| v.as_str() == name)?;
            Some((pass, slot))
        })?;
        name = pass.input(slot.as_str())?.as_str();
    }
    None
}

/// Where an error about an entry goes: the first name it holds, else the file's start.
fn entry_location(source: &Source<'_>, entry: &Entry<'_>) -> Location {
    [
        &entry.name,
        &entry.part,
        &entry.plugin,
        &entry.prefix,
        &entry.when,
    ]
    .into_iter()
    .flatten()
    .next()
    .or_else(|| entry.inputs.0.first().map(|(slot, _)| slot))
    .or_else(|| entry.outputs.0.first().map(|(slot, _)| slot))
    .map_or_else(
        || source.location(crate::position::Position::START),
        |name| source.locate(name),
    )
}

/// `names` comma-separated, or `none` where there are none.
fn listed(names: &[impl AsRef<str>], none: &str) -> String {
    match names.is_empty() {
        true => none.to_owned(),
        false => names
            .iter()
            .map(AsRef::as_ref)
            .collect::<Vec<_>>()
            .join(", "),
    }
}
