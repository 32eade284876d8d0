//! Running one fuzz case: the real `sylva` binary in its own scratch folder, with a time limit,
//! its peak memory read back from the kernel, and the rules every outcome must keep.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// Longest a case may run before it counts as a hang.
pub const TIME_LIMIT: Duration = Duration::from_secs(90);
/// Most memory a case may hold (peak resident set) before it counts as unbounded. Software
/// OpenGL holds up to about 2.7 GB of its own for a big scene.
pub const MEMORY_LIMIT_KB: i64 = 4 << 20;

/// A small deterministic generator (SplitMix64): the same seed replays the same campaign.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// One run of `sylva`.
pub struct Case {
    pub family: &'static str,
    pub args: Vec<String>,
    /// Input files written into the case's folder first.
    pub files: Vec<(String, Vec<u8>)>,
    /// What a refusal must name (a file name, a parameter, a flag), any one of them.
    pub names: Vec<String>,
    /// Environment for the run.
    pub env: Vec<(String, String)>,
}

impl Case {
    pub fn new(family: &'static str, args: &[&str]) -> Self {
        Self {
            family,
            args: args.iter().map(|a| a.to_string()).collect(),
            files: Vec::new(),
            names: Vec::new(),
            env: vec![("SYLVA_RENDERER".into(), "cpu".into())],
        }
    }

    pub fn file(mut self, name: &str, body: Vec<u8>) -> Self {
        self.names.push(name.to_string());
        self.files.push((name.to_string(), body));
        self
    }

    pub fn names(mut self, names: &[&str]) -> Self {
        self.names.extend(names.iter().map(|n| n.to_string()));
        self
    }
}

/// What happened.
pub struct Outcome {
    pub code: Option<i32>,
    pub signal: Option<i32>,
    pub timed_out: bool,
    pub peak_kb: i64,
    pub seconds: f64,
    pub stderr: String,
    /// Files in the folder after the run that were not there before.
    pub left: Vec<String>,
}

fn listing(dir: &Path) -> Vec<String> {
    let mut all = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p.clone());
            }
            all.push(p.strip_prefix(dir).unwrap().display().to_string());
        }
    }
    all.sort();
    all
}

/// Runs `case` in `dir`, which starts empty.
pub fn run(case: &Case, dir: &Path) -> Outcome {
    for (name, body) in &case.files {
        std::fs::write(dir.join(name), body).unwrap();
    }
    let before = listing(dir);
    let stderr_path = dir.join(".stderr");
    let mut command = Command::new(env!("CARGO_BIN_EXE_sylva"));
    command
        .args(&case.args)
        .current_dir(dir)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::fs::File::create(&stderr_path).unwrap());
    for (k, v) in &case.env {
        command.env(k, v);
    }
    let started = Instant::now();
    let child = command.spawn().expect("sylva starts");
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value for wait4 to fill in.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let mut timed_out = false;
    loop {
        // SAFETY: waiting on our own child with valid pointers.
        let done = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        if done == pid {
            break;
        }
        if started.elapsed() > TIME_LIMIT && !timed_out {
            timed_out = true;
            // SAFETY: signalling our own child.
            unsafe { libc::kill(pid, libc::SIGKILL) };
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    std::mem::forget(child);
    let stderr = std::fs::read_to_string(&stderr_path).unwrap_or_default();
    std::fs::remove_file(&stderr_path).unwrap();
    let left = listing(dir)
        .into_iter()
        .filter(|f| !before.contains(f))
        .collect();
    Outcome {
        code: libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status)),
        signal: libc::WIFSIGNALED(status).then(|| libc::WTERMSIG(status)),
        timed_out,
        peak_kb: usage.ru_maxrss,
        seconds: started.elapsed().as_secs_f64(),
        stderr,
        left,
    }
}

/// The rules: an exit of 0, or a refusal (1, or 2 for the argument parser) that says what is
/// wrong, names the input, writes nothing and panics nowhere; never a hang, a signal or
/// memory without bound. `None` when they hold, else what broke.
pub fn broken(case: &Case, o: &Outcome) -> Option<String> {
    if o.timed_out {
        return Some(format!("ran over {} s", TIME_LIMIT.as_secs()));
    }
    if let Some(s) = o.signal {
        return Some(format!("killed by signal {s}"));
    }
    if o.peak_kb > MEMORY_LIMIT_KB {
        return Some(format!("peak memory {} MB", o.peak_kb >> 10));
    }
    if o.stderr.contains("panicked") || o.stderr.contains("RUST_BACKTRACE") {
        return Some("panicked".into());
    }
    match o.code {
        Some(0) => None,
        Some(1 | 2) => {
            if !(o.stderr.starts_with("sylva: ") || o.stderr.starts_with("error: ")) {
                return Some("refused without a message".into());
            }
            if !case.names.is_empty() && !case.names.iter().any(|n| o.stderr.contains(n.as_str())) {
                return Some(format!("the message names none of {:?}", case.names));
            }
            if !o.left.is_empty() {
                return Some(format!("refused but left {:?} behind", o.left));
            }
            None
        }
        Some(c) => Some(format!("exit code {c}")),
        None => Some("no exit status".into()),
    }
}

/// A fresh folder per case under the test's scratch directory.
pub fn scratch(root: &Path, family: &str, index: usize) -> PathBuf {
    let dir = root.join(format!("{family}-{index:04}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
