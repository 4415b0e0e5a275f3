//! One writer per dataset shard: a run of `ehlmap sweep` holds the lock file
//! `<out>/.<name>.<i>of<n>.lock` (next to the dataset directory, like the part files' temporary
//! files, so that the directory holds only Parquet files) while it writes shard i of n.
//!
//! * **Atomic**: the file is created with `O_EXCL` (`create_new`) and holds, as JSON, who holds
//!   it: pid, host, boot id and process start time (Linux), start of the run (UTC), the command
//!   line, the shard and the settings of the spec ([`crate::sweep::settings`]).
//! * **A second run refuses** ([`LockError::Busy`], exit code 1) with a message naming the
//!   holder and the lock file: a run of the same shard; a run of an overlapping shard (shards
//!   i/n and j/m share cases unless i - 1 and j - 1 differ modulo gcd(n, m), e.g. 1/1 and 1/2);
//!   a run of another shard whose spec has other settings.
//! * **Stale locks are taken over** with a warning: on the same host when the holder's process no
//!   longer runs (`kill -9`, a crash, Ctrl-C), has become a zombie, or its pid now belongs to
//!   another process (start times differ), or the host has rebooted; on another host (a shared
//!   file system) when the holder has not refreshed the file's modification time for
//!   [`STALE_AFTER`] (a running holder refreshes it every [`HEARTBEAT`]). The removal happens
//!   under a short-lived `<lock>.takeover` file and only if the lock still holds the stale
//!   holder's bytes, so two runs never both take over the same lock.
//! * **Released** when the [`DatasetLock`] is dropped: on normal exit and on every error return
//!   (the file is removed only while it is still this run's).

use crate::sweep::plan::Shard;
use crate::sweep::settings::Settings;
use serde::{Deserialize, Serialize};
use std::fs::OpenOptions;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// How often a running holder refreshes its lock's modification time.
pub const HEARTBEAT: Duration = Duration::from_secs(60);

/// A lock of another host not refreshed for this long is stale.
pub const STALE_AFTER: Duration = Duration::from_secs(600);

/// A lock file that cannot be parsed (a holder killed between creating and writing it) is
/// stale after this long.
const UNREADABLE_AFTER: Duration = Duration::from_secs(10);

/// A `.takeover` file older than this was left by a killed run and is removed.
const TAKEOVER_STALE: Duration = Duration::from_secs(30);

/// Who holds a lock: the JSON content of the lock file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Holder {
    /// Process id.
    pub pid: u32,
    /// Host name.
    pub host: String,
    /// Linux boot id of the host (a reboot makes every lock of the host stale).
    #[serde(default)]
    pub boot_id: Option<String>,
    /// Start time of the process in clock ticks since boot (Linux, `/proc/<pid>/stat`): tells a
    /// reused pid from the holder.
    #[serde(default)]
    pub proc_start: Option<u64>,
    /// Start of the run, UTC, ISO 8601.
    pub started: String,
    /// The command line of the run.
    pub command: String,
    /// The dataset directory.
    pub dataset: String,
    /// The shard written, `i/n`.
    pub shard: String,
    /// The spec's settings hash ([`Settings::hash`]).
    pub spec_hash: String,
    /// The spec's settings ([`Settings`] text).
    pub spec_settings: String,
    /// Unique to this run (pid and start in ns): the lock is removed only while it holds it.
    pub token: String,
}

impl Holder {
    /// "pid 123 on host since 2025-01-01T00:00:00Z (ehlmap sweep ...)".
    pub fn describe(&self) -> String {
        format!(
            "pid {} on {} since {} ({})",
            self.pid, self.host, self.started, self.command
        )
    }
}

/// Why a lock could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum LockError {
    /// Another run holds the shard, an overlapping shard, or another shard with other settings.
    #[error("{0}")]
    Busy(String),
    /// The lock file could not be created or read.
    #[error("{0}")]
    Io(String),
}

/// The lock of one dataset shard, held until dropped.
#[derive(Debug)]
pub struct DatasetLock {
    path: PathBuf,
    token: String,
    last_beat: Instant,
    lost: bool,
}

/// This host: its name and (Linux) boot id.
struct Host {
    name: String,
    boot_id: Option<String>,
}

fn read_trimmed(path: &str) -> Option<String> {
    let s = std::fs::read_to_string(path).ok()?;
    let s = s.trim();
    (!s.is_empty()).then(|| s.to_string())
}

fn this_host() -> Host {
    let name = read_trimmed("/proc/sys/kernel/hostname")
        .or_else(|| read_trimmed("/etc/hostname"))
        .or_else(|| std::env::var("HOSTNAME").ok().filter(|h| !h.is_empty()))
        .unwrap_or_else(|| "unknown".to_string());
    Host {
        name,
        boot_id: read_trimmed("/proc/sys/kernel/random/boot_id"),
    }
}

/// State letter and start time (ticks since boot) of a process, from `/proc/<pid>/stat`.
fn proc_stat(pid: u32) -> Option<(char, u64)> {
    let s = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) is in parentheses and may hold spaces: split after it.
    let rest = &s[s.rfind(')')? + 1..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let state = f.first()?.chars().next()?;
    let start = f.get(19)?.parse().ok()?;
    Some((state, start))
}

/// Whether process `pid` of this host runs (`None`: cannot tell, no `/proc`). A zombie does not.
fn alive(pid: u32) -> Option<(bool, Option<u64>)> {
    if !Path::new("/proc/self/stat").exists() {
        return None;
    }
    match proc_stat(pid) {
        None => Some((false, None)),
        Some((state, start)) => Some((!matches!(state, 'Z' | 'X' | 'x'), Some(start))),
    }
}

/// The command line of this process, arguments with spaces or quotes single-quoted.
fn command_line() -> String {
    std::env::args()
        .map(|a| {
            if a.is_empty() || a.contains(|c: char| c.is_whitespace() || "'\"\\$`".contains(c)) {
                format!("'{}'", a.replace('\'', "'\\''"))
            } else {
                a
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The lock file of `shard` of the dataset directory `dataset`: `<parent>/.<name>.<i>of<n>.lock`.
pub fn lock_path(dataset: &Path, shard: &Shard) -> PathBuf {
    let (base, name) = base_and_name(dataset);
    base.join(format!(".{name}.{}.lock", shard.label()))
}

fn base_and_name(dataset: &Path) -> (PathBuf, String) {
    let name = dataset
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    let base = match dataset.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    (base, name)
}

/// The shard of a label `<i>of<n>`.
fn parse_label(label: &str) -> Option<Shard> {
    let (i, n) = label.split_once("of")?;
    Shard::parse(&format!("{i}/{n}")).ok()
}

/// The lock files of other shards of the dataset that exist now.
fn other_locks(dataset: &Path, shard: &Shard) -> Vec<(Shard, PathBuf)> {
    let (base, name) = base_and_name(dataset);
    let prefix = format!(".{name}.");
    let mut v = vec![];
    for ent in std::fs::read_dir(&base).into_iter().flatten().flatten() {
        let file = ent.file_name().to_string_lossy().into_owned();
        let label = file
            .strip_prefix(prefix.as_str())
            .and_then(|r| r.strip_suffix(".lock"));
        if let Some(s) = label.and_then(parse_label) {
            if s != *shard {
                v.push((s, ent.path()));
            }
        }
    }
    v.sort_by_key(|(s, _)| (s.count, s.index));
    v
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Whether shards `a` and `b` can hold the same case.
pub fn overlap(a: &Shard, b: &Shard) -> bool {
    let g = gcd(a.count, b.count).max(1);
    (a.index - 1) % g == (b.index - 1) % g
}

/// What a lock file says now.
enum State {
    /// It no longer exists.
    Gone,
    /// Its holder runs (or cannot be shown not to).
    Live(Holder),
    /// Unparseable and young: being written by its creator.
    Starting,
    /// Its holder is gone: the file's bytes, the holder (when parseable) and why.
    Stale {
        bytes: Vec<u8>,
        holder: Option<Holder>,
        why: String,
    },
}

fn age(path: &Path) -> Option<Duration> {
    let m = std::fs::metadata(path).ok()?.modified().ok()?;
    Some(
        SystemTime::now()
            .duration_since(m)
            .unwrap_or(Duration::ZERO),
    )
}

fn minutes(d: Duration) -> String {
    format!("{:.0} min", d.as_secs_f64() / 60.0)
}

/// Read and judge the lock file at `path`.
fn inspect(path: &Path, host: &Host) -> Result<State, LockError> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(State::Gone),
        Err(e) => {
            return Err(LockError::Io(format!(
                "cannot read the lock file {}: {e}",
                path.display()
            )))
        }
    };
    let age = age(path).unwrap_or(Duration::ZERO);
    let Ok(h) = serde_json::from_slice::<Holder>(&bytes) else {
        if age < UNREADABLE_AFTER {
            return Ok(State::Starting);
        }
        return Ok(State::Stale {
            bytes,
            holder: None,
            why: "the file is not a readable lock".to_string(),
        });
    };
    let stale = |why: String| State::Stale {
        bytes: bytes.clone(),
        holder: Some(h.clone()),
        why,
    };
    let by_heartbeat = |what: &str| {
        if age > STALE_AFTER {
            stale(format!(
                "{what}, and the lock was not refreshed for {}",
                minutes(age)
            ))
        } else {
            State::Live(h.clone())
        }
    };
    if h.host != host.name {
        return Ok(by_heartbeat(&format!(
            "the holder runs on another host ({})",
            h.host
        )));
    }
    if let (Some(a), Some(b)) = (&h.boot_id, &host.boot_id) {
        if a != b {
            return Ok(stale(format!("{} has rebooted since", h.host)));
        }
    }
    Ok(match alive(h.pid) {
        None => by_heartbeat("process liveness cannot be checked here"),
        Some((false, _)) => stale(format!("process {} no longer runs", h.pid)),
        Some((true, Some(now))) if h.proc_start.is_some_and(|s| s != now) => {
            stale(format!("pid {} now belongs to another process", h.pid))
        }
        Some((true, _)) => State::Live(h),
    })
}

/// Remove the stale lock at `path` if it still holds `bytes`, under `<path>.takeover`.
fn take_over(path: &Path, bytes: &[u8]) -> Result<(), LockError> {
    let mutex = PathBuf::from(format!("{}.takeover", path.display()));
    let t0 = Instant::now();
    loop {
        match OpenOptions::new().write(true).create_new(true).open(&mutex) {
            Ok(_) => break,
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                if age(&mutex).is_some_and(|a| a > TAKEOVER_STALE) {
                    let _ = std::fs::remove_file(&mutex);
                    continue;
                }
                if t0.elapsed() > 2 * TAKEOVER_STALE {
                    return Err(LockError::Busy(format!(
                        "another run is taking over the lock {} (remove {} if no sweep is starting)",
                        path.display(),
                        mutex.display()
                    )));
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            Err(e) => {
                return Err(LockError::Io(format!(
                    "cannot create {}: {e}",
                    mutex.display()
                )))
            }
        }
    }
    let r = match std::fs::read(path) {
        Ok(now) if now == bytes => std::fs::remove_file(path).map_err(|e| {
            LockError::Io(format!(
                "cannot remove the stale lock {}: {e}",
                path.display()
            ))
        }),
        _ => Ok(()),
    };
    let _ = std::fs::remove_file(&mutex);
    r
}

fn busy_same(dataset: &Path, shard: &Shard, path: &Path, h: &Holder) -> LockError {
    LockError::Busy(format!(
        "shard {shard} of the dataset {} is being written by {}; lock file {} \
         (wait for that run to end; if it is gone from another host, remove the file)",
        dataset.display(),
        h.describe(),
        path.display()
    ))
}

/// Take the lock of `shard` of the dataset directory `dataset` (whose parent must exist) for a
/// run with `settings` started at `started` (ISO 8601). Returns the lock and the warnings to
/// show (stale locks taken over). Refuses ([`LockError::Busy`]) as the module docs say.
pub fn acquire(
    dataset: &Path,
    shard: &Shard,
    settings: &Settings,
    started: &str,
) -> Result<(DatasetLock, Vec<String>), LockError> {
    let path = lock_path(dataset, shard);
    let host = this_host();
    let pid = std::process::id();
    let nanos = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let me = Holder {
        pid,
        host: host.name.clone(),
        boot_id: host.boot_id.clone(),
        proc_start: proc_stat(pid).map(|s| s.1),
        started: started.to_string(),
        command: command_line(),
        dataset: dataset.display().to_string(),
        shard: shard.to_string(),
        spec_hash: settings.hash(),
        spec_settings: settings.to_string(),
        token: format!("{pid}-{nanos}"),
    };
    let text = serde_json::to_string_pretty(&me).expect("a lock serialises") + "\n";
    let mut warnings = vec![];
    let t0 = Instant::now();
    loop {
        match OpenOptions::new().write(true).create_new(true).open(&path) {
            Ok(mut f) => {
                let written = f.write_all(text.as_bytes()).and_then(|_| f.sync_all());
                if let Err(e) = written {
                    let _ = std::fs::remove_file(&path);
                    return Err(LockError::Io(format!(
                        "cannot write the lock file {}: {e}",
                        path.display()
                    )));
                }
                break;
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                match inspect(&path, &host)? {
                    State::Gone => {}
                    State::Live(h) => return Err(busy_same(dataset, shard, &path, &h)),
                    State::Starting => std::thread::sleep(Duration::from_millis(50)),
                    State::Stale { bytes, holder, why } => {
                        take_over(&path, &bytes)?;
                        let who = holder.map_or("an unknown run".to_string(), |h| h.describe());
                        warnings.push(format!(
                            "took over the stale lock {} of {who}: {why}; the cases that run \
                             flushed are kept, the others are solved now",
                            path.display()
                        ));
                    }
                }
                if t0.elapsed() > UNREADABLE_AFTER + TAKEOVER_STALE * 2 {
                    return Err(LockError::Busy(format!(
                        "cannot take the lock {} (it keeps changing)",
                        path.display()
                    )));
                }
            }
            Err(e) => {
                return Err(LockError::Io(format!(
                    "cannot create the lock file {}: {e}",
                    path.display()
                )))
            }
        }
    }
    let lock = DatasetLock {
        path,
        token: me.token,
        last_beat: Instant::now(),
        lost: false,
    };
    // Other shards: refuse an overlapping shard or other settings while their holder runs.
    for (other, p) in other_locks(dataset, shard) {
        let mut state = inspect(&p, &host)?;
        // A lock being created this instant: wait for its content (it is stale after a while).
        while matches!(state, State::Starting) {
            std::thread::sleep(Duration::from_millis(50));
            state = inspect(&p, &host)?;
        }
        let State::Live(h) = state else {
            continue;
        };
        if overlap(shard, &other) {
            return Err(LockError::Busy(format!(
                "shard {shard} of the dataset {} overlaps shard {other}, which {} is writing; \
                 lock file {} (shards i/n and j/m share cases unless i - 1 and j - 1 differ \
                 modulo gcd(n, m))",
                dataset.display(),
                h.describe(),
                p.display()
            )));
        }
        let theirs = Settings::parse(&h.spec_settings).unwrap_or_default();
        let diff = settings.conflicts(&theirs);
        if !diff.is_empty() {
            let list: Vec<String> = diff
                .iter()
                .map(|d| format!("{}: {} there, {} in this spec", d.key, d.theirs, d.ours))
                .collect();
            return Err(LockError::Busy(format!(
                "shard {other} of the dataset {} is being written by {} with other settings \
                 ({}); lock file {}",
                dataset.display(),
                h.describe(),
                list.join(", "),
                p.display()
            )));
        }
    }
    Ok((lock, warnings))
}

impl DatasetLock {
    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether the file still holds this run's lock.
    fn ours(&self) -> bool {
        std::fs::read(&self.path)
            .ok()
            .and_then(|b| serde_json::from_slice::<Holder>(&b).ok())
            .is_some_and(|h| h.token == self.token)
    }

    /// Refresh the lock's modification time when [`HEARTBEAT`] has passed since the last time
    /// (call it often). Returns a warning, once, when the lock is no longer this run's (removed
    /// by hand, or taken over by a run that judged it stale).
    pub fn heartbeat(&mut self) -> Option<String> {
        if self.lost || self.last_beat.elapsed() < HEARTBEAT {
            return None;
        }
        self.last_beat = Instant::now();
        if self.ours() {
            if let Ok(f) = OpenOptions::new().write(true).open(&self.path) {
                let _ = f.set_modified(SystemTime::now());
            }
            return None;
        }
        self.lost = true;
        Some(format!(
            "the lock {} is no longer this run's (removed, or taken over as stale): another \
             run may now write the same cases (readers keep one row per case)",
            self.path.display()
        ))
    }
}

impl Drop for DatasetLock {
    fn drop(&mut self) {
        if self.ours() {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_overlap_unless_residues_differ_modulo_the_gcd() {
        let s = |i, n| Shard { index: i, count: n };
        assert!(overlap(&s(1, 1), &s(2, 2)));
        assert!(overlap(&s(1, 2), &s(3, 4)));
        assert!(!overlap(&s(1, 2), &s(2, 4)));
        assert!(!overlap(&s(1, 2), &s(2, 2)));
        assert!(overlap(&s(2, 3), &s(1, 2)));
        assert_eq!(parse_label("2of8"), Some(s(2, 8)));
        assert_eq!(parse_label("9of8"), None);
        assert_eq!(
            lock_path(Path::new("out/smoke"), &s(1, 2)),
            Path::new("out/.smoke.1of2.lock")
        );
        assert_eq!(
            lock_path(Path::new("smoke"), &s(1, 1)),
            Path::new("./.smoke.1of1.lock")
        );
    }

    #[test]
    fn this_process_is_alive_with_a_start_time() {
        if let Some((alive, start)) = alive(std::process::id()) {
            assert!(alive && start.is_some());
            assert_eq!(alive_of(u32::MAX), Some(false));
        }
    }

    fn alive_of(pid: u32) -> Option<bool> {
        alive(pid).map(|a| a.0)
    }
}
