//! Files written completely or not at all: every writer of the workspace (the command's `-o`,
//! `--report` and `--plot`, CAD exports, `fair lines`' files) goes through [`Outputs`] or
//! [`write_file`].
//!
//! A run's outputs are written in two phases. First each regular file is written to a
//! temporary file beside its target, `.<name>.fair-tmp-<pid>-<n>` in the target's directory
//! (so that the rename below stays within one file system), and flushed to disk (`fsync`).
//! Only when every one of them was written are they renamed over their targets, one after the
//! other (the commit). Until the commit the old targets are untouched; a failure before it
//! removes the temporary files and leaves no new file. The commit is a sequence of renames,
//! each atomic on its own (a reader sees the old file or the new one, never a prefix), but not
//! jointly atomic: a process killed between two renames has replaced some targets and not
//! the others, each of them whole. A process killed by SIGKILL before its commit can leave a
//! temporary file behind; its name (a dot, the target's name, `.fair-tmp-`) says what it is,
//! and it can be deleted.
//!
//! Targets that are not regular files are written in place, since renaming over them would
//! replace the device or FIFO itself (`/dev/null`): an existing character or block device,
//! FIFO or socket is opened and written directly, after every temporary file was written and
//! before the renames, so that `/dev/full` fails the run while nothing new is in place yet.
//! Standard output ([`Target::Stdout`]) is written at the same moment; a closed pipe
//! (`fair … -o - | head`) is not an error. A symbolic link is followed: the file it points to
//! is replaced and the link kept. A replaced file keeps its permissions; a new one gets the
//! usual `0666` less the umask. A replaced file's other hard links keep the old content.
//!
//! Cost: each output is written once, plus one `fsync` per file and one per directory.

use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Where an output goes.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Target {
    /// Standard output (the command line's `-`).
    Stdout,
    /// A file.
    File(PathBuf),
}

impl Target {
    /// The command line's convention: `-` is standard output, anything else a file.
    pub fn from_arg(arg: impl AsRef<Path>) -> Self {
        let arg = arg.as_ref();
        if arg.as_os_str() == "-" {
            Target::Stdout
        } else {
            Target::File(arg.to_path_buf())
        }
    }

    /// What error messages call it: the path as given, or `<stdout>`.
    pub fn name(&self) -> String {
        match self {
            Target::Stdout => "<stdout>".into(),
            Target::File(path) => path.display().to_string(),
        }
    }

    /// A key equal for two targets that name the same file: standard output; an existing
    /// path with its symbolic links resolved; a new one under its canonical directory
    /// (`./x.csv` and `x.csv` are one file). A path whose directory does not exist is kept
    /// as given (the write will fail and say so). O(path length) system calls.
    fn identity(&self) -> Target {
        let Target::File(path) = self else {
            return Target::Stdout;
        };
        if let Ok(full) = std::fs::canonicalize(path) {
            return Target::File(full);
        }
        let dir = match path.parent() {
            Some(dir) if !dir.as_os_str().is_empty() => dir,
            _ => Path::new("."),
        };
        match (std::fs::canonicalize(dir), path.file_name()) {
            (Ok(dir), Some(name)) => Target::File(dir.join(name)),
            _ => Target::File(path.clone()),
        }
    }
}

/// Two outputs of one run that name one file (`-o x.csv --report ./x.csv`): the flags that
/// name it, in the order given, and the path as the second gives it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Clash {
    /// The flag given first (`-o`).
    pub first: String,
    /// The flag given second (`--report`).
    pub second: String,
    /// The path as the second flag spells it.
    pub path: String,
}

impl std::fmt::Display for Clash {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} and {} both name {}: one would overwrite the other; give them different files",
            self.first, self.second, self.path
        )
    }
}

/// The first pair of `outputs` (flag, target) that name one file ([`Target`]'s identity:
/// symbolic links and `.` resolved), or `None`. For checking a command line before anything
/// runs. An existing device or FIFO named twice is no clash (`/dev/null` takes both); standard
/// output twice is. O(n²) in the number of outputs, a handful.
pub fn find_clash<'f>(outputs: impl IntoIterator<Item = (&'f str, Target)>) -> Option<Clash> {
    let keyed: Vec<(&str, Target, Target)> = outputs
        .into_iter()
        .map(|(flag, target)| {
            let key = target.identity();
            (flag, target, key)
        })
        .collect();
    for (i, (second, target, key)) in keyed.iter().enumerate() {
        if let Target::File(path) = key {
            if std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
                continue;
            }
        }
        if let Some((first, _, _)) = keyed[..i].iter().find(|(_, _, k)| k == key) {
            return Some(Clash {
                first: first.to_string(),
                second: second.to_string(),
                path: target.name(),
            });
        }
    }
    None
}

/// A write that failed: the target as given and the system's error.
#[derive(Debug)]
pub struct WriteError {
    /// The output that could not be written.
    pub target: Target,
    /// Why.
    pub error: io::Error,
}

impl std::fmt::Display for WriteError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.target.name(), self.error)
    }
}

impl std::error::Error for WriteError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// What writes one output's bytes into the writer it is given (buffered).
pub type Content<'a> = Box<dyn FnOnce(&mut dyn Write) -> io::Result<()> + 'a>;

/// The outputs of one run, written all together by [`Outputs::commit`] (the module's doc).
/// Dropped without a commit, it writes nothing.
#[derive(Default)]
pub struct Outputs<'a> {
    pending: Vec<(Target, Content<'a>)>,
}

impl std::fmt::Debug for Outputs<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list()
            .entries(self.pending.iter().map(|(t, _)| t))
            .finish()
    }
}

/// A temporary file written and waiting for its rename; removed when dropped unless renamed.
struct Staged {
    temp: PathBuf,
    target: PathBuf,
    given: Target,
    renamed: bool,
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.renamed {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

impl<'a> Outputs<'a> {
    /// No outputs yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds an output: `content` writes its bytes when [`commit`](Self::commit) runs.
    pub fn add(&mut self, target: Target, content: impl FnOnce(&mut dyn Write) -> io::Result<()> + 'a) {
        self.pending.push((target, Box::new(content)));
    }

    /// Adds an output whose bytes are `text`.
    pub fn add_text(&mut self, target: Target, text: impl AsRef<[u8]> + 'a) {
        self.add(target, move |w| w.write_all(text.as_ref()));
    }

    /// Whether nothing was added.
    pub fn is_empty(&self) -> bool {
        self.pending.is_empty()
    }

    /// Writes every output: the regular files to temporary files (each flushed to disk),
    /// then the devices and standard output in place, then renames the temporary files over
    /// their targets in the order added. The first failure stops it: before the renames, no
    /// target file was changed and the temporary files are gone; a rename that fails (rare:
    /// the directory changed under the run) leaves the earlier targets replaced, the others
    /// old. The error names the output as it was given.
    pub fn commit(self) -> Result<(), WriteError> {
        let (mut files, mut direct) = (Vec::new(), Vec::new());
        for (given, content) in self.pending {
            match &given {
                Target::Stdout => direct.push((given, None, content)),
                Target::File(path) => match resolve(path) {
                    Resolved::Regular(target) => files.push((given, target, content)),
                    Resolved::Special(target) => direct.push((given, Some(target), content)),
                },
            }
        }
        let mut staged = Vec::with_capacity(files.len());
        for (given, target, content) in files {
            let failed = |error| WriteError {
                target: given.clone(),
                error,
            };
            let (file, temp) = create_temp(&target).map_err(failed)?;
            // Registered before the write, so that a failing write removes it.
            staged.push(Staged {
                temp,
                target,
                given: given.clone(),
                renamed: false,
            });
            write_through(file, content).map_err(failed)?;
        }
        for (given, target, content) in direct {
            let result = match &target {
                None => write_stdout(content),
                Some(path) => std::fs::OpenOptions::new()
                    .write(true)
                    .truncate(true)
                    .open(path)
                    .and_then(|file| write_through_unsynced(file, content)),
            };
            result.map_err(|error| WriteError { target: given, error })?;
        }
        let mut directories = Vec::new();
        for file in &mut staged {
            std::fs::rename(&file.temp, &file.target).map_err(|error| WriteError {
                target: file.given.clone(),
                error,
            })?;
            file.renamed = true;
            let dir = directory_of(&file.target).to_path_buf();
            if !directories.contains(&dir) {
                directories.push(dir);
            }
        }
        // The renames to disk too; a file system that cannot sync a directory is not an error.
        for dir in directories {
            sync_directory(&dir);
        }
        Ok(())
    }
}

/// Writes one file completely or not at all ([`Outputs`] with one output).
pub fn write_file(
    target: impl AsRef<Path>,
    content: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), WriteError> {
    let mut outputs = Outputs::new();
    outputs.add(Target::File(target.as_ref().to_path_buf()), content);
    outputs.commit()
}

/// [`write_file`] of `text`.
pub fn write_text(target: impl AsRef<Path>, text: impl AsRef<[u8]>) -> Result<(), WriteError> {
    write_file(target, |w| w.write_all(text.as_ref()))
}

/// Where a file target's bytes go.
enum Resolved {
    /// Through a temporary file renamed over this path (it may not exist yet).
    Regular(PathBuf),
    /// Into this existing device, FIFO or socket, directly.
    Special(PathBuf),
}

fn resolve(path: &Path) -> Resolved {
    // A symbolic link (even a chain of them) is replaced at the file it points to.
    let target = match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => {
            std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
        }
        _ => path.to_path_buf(),
    };
    match std::fs::metadata(&target) {
        Ok(meta) if !meta.is_file() && !meta.is_dir() => Resolved::Special(target),
        _ => Resolved::Regular(target),
    }
}

/// The directory a target's temporary file goes in (`.` for a bare name).
fn directory_of(target: &Path) -> &Path {
    match target.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}

/// A fresh `.<name>.fair-tmp-<pid>-<n>` beside `target`, opened for writing, with the
/// target's permissions when it exists. Fails as creating a file in that directory fails (no
/// such directory, permission denied); a target that is a directory fails here too.
fn create_temp(target: &Path) -> io::Result<(std::fs::File, PathBuf)> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let old = std::fs::metadata(target).ok();
    if old.as_ref().is_some_and(|m| m.is_dir()) {
        return Err(io::Error::new(io::ErrorKind::IsADirectory, "it is a directory"));
    }
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    let dir = directory_of(target);
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(format!(".{name}.fair-tmp-{}-{n}", std::process::id()));
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temp)
        {
            Ok(file) => {
                if let Some(old) = &old {
                    // Best effort: a file system without permissions (FAT) keeps its default.
                    let _ = file.set_permissions(old.permissions());
                }
                return Ok((file, temp));
            }
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

/// `content` into `file` through a buffer, then flushed to disk.
fn write_through(file: std::fs::File, content: Content<'_>) -> io::Result<()> {
    let mut writer = io::BufWriter::with_capacity(1 << 16, file);
    content(&mut writer)?;
    let file = writer.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()
}

/// `content` into a device or FIFO through a buffer (no `fsync`: a device may not have one).
fn write_through_unsynced(file: std::fs::File, content: Content<'_>) -> io::Result<()> {
    let mut writer = io::BufWriter::with_capacity(1 << 16, file);
    content(&mut writer)?;
    writer.flush()
}

/// `content` to standard output; a closed pipe is not an error.
fn write_stdout(content: Content<'_>) -> io::Result<()> {
    let mut writer = io::BufWriter::with_capacity(1 << 16, io::stdout().lock());
    match content(&mut writer).and_then(|()| writer.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

#[cfg(unix)]
fn sync_directory(dir: &Path) {
    if let Ok(handle) = std::fs::File::open(dir) {
        let _ = handle.sync_all();
    }
}

#[cfg(not(unix))]
fn sync_directory(_dir: &Path) {}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_failing_writer_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.csv");
        std::fs::write(&path, "old\n").unwrap();
        let e = write_file(&path, |w| {
            // More than the buffer, so that part of it reached the temporary file.
            w.write_all(&vec![b'x'; 200_000])?;
            Err(io::Error::other("disk on fire"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), format!("{}: disk on fire", path.display()));
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old\n");
        assert_eq!(entries(dir.path()), ["out.csv"]);
    }

    #[test]
    fn one_failing_output_writes_none_of_the_others() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b, c) = (dir.path().join("a"), dir.path().join("b"), dir.path().join("c"));
        std::fs::write(&a, "old a").unwrap();
        let mut outputs = Outputs::new();
        outputs.add_text(Target::File(a.clone()), "new a");
        outputs.add_text(Target::File(b.clone()), "new b");
        outputs.add(Target::File(c), |_| Err(io::Error::other("no")));
        assert!(outputs.commit().is_err());
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a");
        assert_eq!(entries(dir.path()), ["a"]);
    }

    #[test]
    fn a_commit_replaces_every_file_keeping_permissions() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a"), dir.path().join("b"));
        std::fs::write(&a, "old a, longer than the new").unwrap();
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(&a, std::fs::Permissions::from_mode(0o640)).unwrap();
        }
        let mut outputs = Outputs::new();
        outputs.add_text(Target::File(a.clone()), "new a");
        outputs.add_text(Target::File(b.clone()), String::from("new b"));
        outputs.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "new a");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "new b");
        assert_eq!(entries(dir.path()), ["a", "b"]);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&a).unwrap().permissions().mode() & 0o777;
            assert_eq!(mode, 0o640);
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_symbolic_link_is_kept_and_its_file_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let (real, link) = (dir.path().join("real.csv"), dir.path().join("link.csv"));
        std::fs::write(&real, "old").unwrap();
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_text(&link, "new").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read_to_string(&real).unwrap(), "new");
        assert_eq!(entries(dir.path()), ["link.csv", "real.csv"]);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn devices_are_written_in_place() {
        write_text("/dev/null", "nothing").unwrap();
        assert!(!std::fs::metadata("/dev/null").unwrap().file_type().is_file());
        let e = write_text("/dev/full", "x".repeat(100)).unwrap_err();
        assert_eq!(e.target, Target::File("/dev/full".into()));
        assert_eq!(e.error.raw_os_error(), Some(28), "{e}"); // ENOSPC
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_full_device_fails_the_run_before_any_rename() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a");
        std::fs::write(&a, "old a").unwrap();
        let mut outputs = Outputs::new();
        outputs.add_text(Target::File(a.clone()), "new a");
        outputs.add_text(Target::File("/dev/full".into()), "report");
        assert!(outputs.commit().is_err());
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a");
        assert_eq!(entries(dir.path()), ["a"]);
    }

    #[test]
    fn a_missing_directory_or_a_directory_target_fails() {
        let dir = tempfile::tempdir().unwrap();
        let e = write_text(dir.path().join("no/such/x.csv"), "x").unwrap_err();
        assert_eq!(e.error.kind(), io::ErrorKind::NotFound);
        let e = write_text(dir.path(), "x").unwrap_err();
        assert_eq!(e.error.kind(), io::ErrorKind::IsADirectory);
        assert!(entries(dir.path()).is_empty());
    }

    #[test]
    fn clashes_are_found_through_dot_and_links() {
        let dir = tempfile::tempdir().unwrap();
        let x = dir.path().join("x.csv");
        let dotted = dir.path().join(".").join("x.csv");
        let clash = find_clash([
            ("-o", Target::File(x.clone())),
            ("--plot", Target::File(dir.path().join("p.svg"))),
            ("--report", Target::File(dotted.clone())),
        ])
        .unwrap();
        assert_eq!((clash.first.as_str(), clash.second.as_str()), ("-o", "--report"));
        assert_eq!(clash.path, dotted.display().to_string());
        assert!(
            clash.to_string().starts_with("-o and --report both name "),
            "{clash}"
        );
        assert_eq!(
            find_clash([("-o", Target::Stdout), ("--report", Target::Stdout)])
                .unwrap()
                .path,
            "<stdout>"
        );
        #[cfg(unix)]
        assert_eq!(
            find_clash([
                ("-o", Target::File("/dev/null".into())),
                ("--report", Target::File("/dev/null".into()))
            ]),
            None
        );
        assert_eq!(
            find_clash([
                ("-o", Target::File(x.clone())),
                ("--report", Target::File(dir.path().join("y.csv")))
            ]),
            None
        );
        #[cfg(unix)]
        {
            std::fs::write(&x, "").unwrap();
            let link = dir.path().join("link.csv");
            std::os::unix::fs::symlink(&x, &link).unwrap();
            assert!(find_clash([("-o", Target::File(x)), ("--report", Target::File(link))]).is_some());
        }
    }
}
