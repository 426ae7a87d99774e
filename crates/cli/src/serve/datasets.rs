//! The data sets the page offers: the embedded ones (those of `fair demo`, in the binary) and
//! the files and folders named on the command line.
//!
//! The list is made once, at start: a file is offered under its file name, every curve file
//! inside a folder (`.csv`, `.json`, `.dat`, `.txt`; hidden entries skipped) under
//! `FOLDER/relative/path`. A request names an entry of that list, nothing else: a name with a
//! `..` component, an absolute path or a backslash is refused as outside the data folder, an
//! unknown name is not found, and a listed file that a symbolic link (made since) leads out of
//! its folder is refused when read.

use std::path::{Component, Path, PathBuf};

use crate::input::embedded::DATASETS;
use crate::input::Source;
use fair_door::error::{Error, Result};

/// File extensions offered from a folder.
pub(crate) const EXTENSIONS: [&str; 4] = ["csv", "json", "dat", "txt"];

/// The most files offered from the folders given (the walk stops there).
pub(crate) const MAX_FILES: usize = 10_000;

/// The deepest folder level walked below a folder given.
pub(crate) const MAX_DEPTH: usize = 8;

/// Where an entry's text comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Origin {
    /// Text in the binary.
    Embedded(&'static str),
    /// A file given on the command line.
    File(PathBuf),
    /// A file inside a folder given on the command line: the file, and the folder
    /// (canonical) it must stay inside.
    InFolder(PathBuf, PathBuf),
}

/// One data set.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Dataset {
    /// The name the API takes.
    pub name: String,
    /// One line on what it is.
    pub about: String,
    /// Where its text comes from.
    pub origin: Origin,
}

impl Dataset {
    /// `embedded` or `file`.
    pub(crate) fn origin_name(&self) -> &'static str {
        match self.origin {
            Origin::Embedded(_) => "embedded",
            Origin::File(_) | Origin::InFolder(..) => "file",
        }
    }
}

/// Why a data set cannot be given.
#[derive(Debug)]
pub(crate) enum Unavailable {
    /// The name reaches outside the data folders (400).
    Outside(String),
    /// No data set has this name (404).
    Unknown(String),
    /// The file is larger than the limit (413).
    TooLarge(String),
    /// It cannot be read (the file went away, is not UTF-8, ...) (400).
    Unreadable(Error),
}

/// The list of data sets.
#[derive(Debug, Clone, Default)]
pub(crate) struct Datasets {
    entries: Vec<Dataset>,
}

impl Datasets {
    /// The embedded data sets, then each file given and every curve file in each folder
    /// given. Fails (exit status 2) for a path that is neither.
    pub(crate) fn new(paths: &[PathBuf]) -> Result<Datasets> {
        let mut entries: Vec<Dataset> = DATASETS
            .iter()
            .map(|d| Dataset {
                name: d.name.to_string(),
                about: d.about.to_string(),
                origin: Origin::Embedded(d.text),
            })
            .collect();
        for path in paths {
            let shown = path.display().to_string();
            if path.is_file() {
                let name = path
                    .file_name()
                    .map(|n| n.to_string_lossy().to_string())
                    .unwrap_or_else(|| shown.clone());
                push_unique(
                    &mut entries,
                    Dataset {
                        about: format!("the file {name} given to fair serve"),
                        name,
                        origin: Origin::File(path.clone()),
                    },
                );
            } else if path.is_dir() {
                let root = path.canonicalize().map_err(|e| Error::Read {
                    path: shown.clone(),
                    reason: fair_door::error::io_reason(&e),
                })?;
                let label = root
                    .file_name()
                    .map(|n| n.to_string_lossy().to_string())
                    .unwrap_or_else(|| "data".into());
                let mut files = Vec::new();
                walk(&root, 0, &mut files);
                files.sort();
                for file in files {
                    let relative = file.strip_prefix(&root).unwrap_or(&file);
                    let relative: Vec<String> = relative
                        .components()
                        .map(|c| c.as_os_str().to_string_lossy().to_string())
                        .collect();
                    let name = format!("{label}/{}", relative.join("/"));
                    push_unique(
                        &mut entries,
                        Dataset {
                            // The server's own paths stay private: the name is relative.
                            about: format!("the file {name} of a folder given to fair serve"),
                            name,
                            origin: Origin::InFolder(file, root.clone()),
                        },
                    );
                }
            } else {
                return Err(Error::Read {
                    path: shown,
                    reason: "no such file or directory".into(),
                });
            }
        }
        Ok(Datasets { entries })
    }

    /// Every data set, embedded ones first.
    pub(crate) fn list(&self) -> &[Dataset] {
        &self.entries
    }

    /// The data set called `name`, its text read now (at most `limit` bytes).
    pub(crate) fn read(
        &self,
        name: &str,
        limit: usize,
    ) -> std::result::Result<(&Dataset, Source), Unavailable> {
        if outside(name) {
            return Err(Unavailable::Outside(name.to_string()));
        }
        let entry = self
            .entries
            .iter()
            .find(|e| e.name == name)
            .ok_or_else(|| Unavailable::Unknown(name.to_string()))?;
        let path = match &entry.origin {
            Origin::Embedded(text) => return Ok((entry, Source::from_text(&entry.name, text))),
            Origin::File(path) => path.clone(),
            Origin::InFolder(path, root) => {
                let real = path.canonicalize().map_err(|e| {
                    Unavailable::Unreadable(Error::Read {
                        path: entry.name.clone(),
                        reason: fair_door::error::io_reason(&e),
                    })
                })?;
                if !real.starts_with(root) {
                    return Err(Unavailable::Outside(name.to_string()));
                }
                real
            }
        };
        // A regular file only: a FIFO or device put in a listed file's place would block the
        // reader (or never end).
        let metadata = std::fs::metadata(&path).map_err(|e| {
            Unavailable::Unreadable(Error::Read {
                path: entry.name.clone(),
                reason: crate::input::io_reason(&e),
            })
        })?;
        if !metadata.is_file() {
            return Err(Unavailable::Unreadable(Error::Read {
                path: entry.name.clone(),
                reason: "not a regular file".into(),
            }));
        }
        let size = metadata.len();
        if size > limit as u64 {
            return Err(Unavailable::TooLarge(format!(
                "{name}: {size} bytes, more than the limit of {limit} (fair serve --max-upload)"
            )));
        }
        let mut source = Source::read(&path.display().to_string()).map_err(|e| {
            Unavailable::Unreadable(match e {
                Error::Read { reason, .. } => Error::Read {
                    path: entry.name.clone(),
                    reason,
                },
                other => other,
            })
        })?;
        // Messages name the data set, not the server's path to it.
        source.name = entry.name.clone();
        Ok((entry, source))
    }
}

/// Whether a requested name reaches outside the data folders: `..`, a root, a drive prefix,
/// a backslash or a NUL.
pub(crate) fn outside(name: &str) -> bool {
    name.contains('\\')
        || name.contains('\0')
        || name.starts_with('/')
        || Path::new(name)
            .components()
            .any(|c| !matches!(c, Component::Normal(_) | Component::CurDir))
}

fn push_unique(entries: &mut Vec<Dataset>, mut entry: Dataset) {
    let base = entry.name.clone();
    let mut k = 2;
    while entries.iter().any(|e| e.name == entry.name) {
        entry.name = format!("{base} ({k})");
        k += 1;
    }
    entries.push(entry);
}

fn walk(dir: &Path, depth: usize, files: &mut Vec<PathBuf>) {
    if depth > MAX_DEPTH || files.len() >= MAX_FILES {
        return;
    }
    let Ok(read) = std::fs::read_dir(dir) else { return };
    let mut children: Vec<PathBuf> = read
        .flatten()
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .map(|e| e.path())
        .collect();
    children.sort();
    for child in children {
        if files.len() >= MAX_FILES {
            return;
        }
        // Symbolic links are not followed out of the folder (checked again on reading).
        let Ok(meta) = std::fs::symlink_metadata(&child) else {
            continue;
        };
        if meta.is_dir() {
            walk(&child, depth + 1, files);
        } else if meta.is_file() {
            let extension = child
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            if extension.is_some_and(|e| EXTENSIONS.contains(&e.as_str())) {
                files.push(child);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_outside_are_refused() {
        for bad in [
            "../x.csv",
            "a/../../b",
            "/etc/passwd",
            "a\\b",
            "..",
            "a/..",
            "x\0",
        ] {
            assert!(outside(bad), "{bad}");
        }
        for good in ["gunnerus-wl03", "data/a/b.csv", "./a.csv", "a..b.csv"] {
            assert!(!outside(good), "{good}");
        }
    }

    #[test]
    fn folders_and_files_are_listed_and_read_within_limits() {
        let scratch = tempfile::Builder::new()
            .prefix("fair-serve-datasets-")
            .tempdir()
            .unwrap();
        let dir = scratch.path();
        let sub = dir.join("curves");
        std::fs::create_dir_all(sub.join("deep")).unwrap();
        std::fs::write(sub.join("a.csv"), "0,0\n1,1\n2,0\n").unwrap();
        std::fs::write(sub.join("deep/b.dat"), "name\n1 0\n0 0\n1 0.1\n").unwrap();
        std::fs::write(sub.join("notes.md"), "not data").unwrap();
        std::fs::write(sub.join(".hidden.csv"), "0,0\n").unwrap();
        let single = dir.join("single.csv");
        std::fs::write(&single, "0,0\n1,2\n2,0\n").unwrap();
        let sets = Datasets::new(&[sub.clone(), single.clone()]).unwrap();
        let names: Vec<&str> = sets.list().iter().map(|d| d.name.as_str()).collect();
        assert_eq!(
            names[..DATASETS.len()],
            DATASETS.iter().map(|d| d.name).collect::<Vec<_>>()[..]
        );
        assert_eq!(
            &names[DATASETS.len()..],
            ["curves/a.csv", "curves/deep/b.dat", "single.csv"]
        );
        let (entry, source) = sets.read("curves/a.csv", 1000).unwrap();
        assert_eq!(entry.origin_name(), "file");
        assert_eq!(source.text, "0,0\n1,1\n2,0\n");
        assert_eq!(source.name, "curves/a.csv");
        assert!(matches!(
            sets.read("curves/a.csv", 5),
            Err(Unavailable::TooLarge(m)) if m == "curves/a.csv: 12 bytes, more than the limit of 5 (fair serve --max-upload)"
        ));
        assert!(matches!(
            sets.read("curves/notes.md", 1000),
            Err(Unavailable::Unknown(_))
        ));
        assert!(matches!(
            sets.read("curves/../single.csv", 1000),
            Err(Unavailable::Outside(_))
        ));
        let (embedded, source) = sets.read(DATASETS[0].name, 0).unwrap();
        assert_eq!(embedded.origin_name(), "embedded");
        assert_eq!(source.text, DATASETS[0].text);
        assert!(Datasets::new(&[dir.join("missing.csv")]).is_err());
    }
}
