//! Bounded-time fuzz of the command line (issue 12): seeded mutations of catalogue
//! scenes — a value scaled to an extreme, zeroed, negated or replaced by a wrong type, a
//! key repeated, a byte-order mark — solved with `--json`. Every run must exit 0 or 2
//! without a panic; an exit 0 writes a result whose every number is finite and prints
//! no NaN; an exit 2 leaves neither the result nor a temporary file. A run that takes
//! longer than [`RUN_LIMIT`] is stopped and counted, not judged (a slow extreme is no
//! wrong answer); the whole test stops after [`BUDGET`].

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod common;

/// Wall time of the whole fuzz run (CI budget ~20 s with the build already done).
const BUDGET: Duration = Duration::from_secs(12);
/// Wall time of one solve before it is stopped.
const RUN_LIMIT: Duration = Duration::from_secs(4);

struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 33) as usize % n.max(1)
    }
}

/// Pointers to every number in the document.
fn numbers(v: &serde_json::Value, pointer: String, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => m.iter().for_each(|(k, c)| numbers(c, format!("{pointer}/{k}"), out)),
        serde_json::Value::Array(a) => a.iter().enumerate().for_each(|(i, c)| numbers(c, format!("{pointer}/{i}"), out)),
        serde_json::Value::Number(_) => out.push(pointer),
        _ => {}
    }
}

/// One mutated scene text and a description of the mutation.
fn mutate(rng: &mut Rng, text: &str) -> (String, String) {
    let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
    let mut spots = Vec::new();
    numbers(&v, String::new(), &mut spots);
    let spot = spots[rng.below(spots.len())].clone();
    let old = v.pointer(&spot).and_then(serde_json::Value::as_f64).unwrap_or(1.0);
    let new = match rng.below(9) {
        0 => serde_json::json!(0.0),
        1 => serde_json::json!(-old),
        2 => serde_json::json!(old * 1e6),
        3 => serde_json::json!(old * 1e-6),
        4 => serde_json::json!(1e300),
        5 => serde_json::json!("NaN"),
        6 => serde_json::json!([old]),
        7 => serde_json::json!(old * 1.5),
        _ => {
            // a repeated key: the original line doubled in the text
            let key = spot.rsplit('/').next().unwrap().to_string();
            let needle = format!("\"{key}\": ");
            if let Some(i) = text.find(&needle) {
                let end = i + text[i..].find([',', '\n']).unwrap();
                let doubled = format!("{}{}, {}", &text[..end], &text[i..end], &text[end..]);
                return (doubled, format!("{key} repeated"));
            }
            serde_json::json!(old)
        }
    };
    let what = format!("{spot} = {new}");
    *v.pointer_mut(&spot).unwrap() = new;
    let text = serde_json::to_string_pretty(&v).unwrap();
    if rng.below(5) == 0 {
        (format!("\u{FEFF}{text}"), format!("{what} with BOM"))
    } else {
        (text, what)
    }
}

/// Runs the binary, stopping it after [`RUN_LIMIT`]; `None` if it was stopped.
fn run_bounded(args: &[&str]) -> Option<std::process::Output> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_beltcheck"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let start = Instant::now();
    loop {
        if child.try_wait().expect("wait").is_some() {
            return Some(child.wait_with_output().expect("output"));
        }
        if start.elapsed() > RUN_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            return None;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn no_nan(what: &str, text: &str) {
    let bad = text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.')).find(|t| matches!(t.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity"));
    assert!(bad.is_none(), "{what}: non-finite number in output:\n{text}");
}

#[test]
fn mutated_catalogue_scenes_through_the_cli() {
    let start = Instant::now();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scenes = ["string-hanging", "string-hanging-slack", "string-hanging-steel", "rod-hanging", "string-drive"];
    let texts: Vec<String> = scenes.iter().map(|s| std::fs::read_to_string(root.join(format!("scenes/{s}.json"))).unwrap()).collect();
    let dir: PathBuf = common::temp("cli-fuzz", "runs");
    std::fs::create_dir_all(&dir).unwrap();
    let mut rng = Rng(0x005e_ed0f_be17_c0de);
    let (mut ok, mut refused, mut stopped) = (0, 0, 0);
    for case in 0.. {
        if start.elapsed() > BUDGET {
            break;
        }
        let k = rng.below(scenes.len());
        let (text, what) = mutate(&mut rng, &texts[k]);
        let scene = dir.join(format!("case{case}.json"));
        std::fs::write(&scene, &text).unwrap();
        let out = dir.join(format!("case{case}.out.json"));
        let method: &[&str] = match (scenes[k], rng.below(3)) {
            ("string-drive", _) | (_, 0 | 1) => &["--method", "bvp-collocation"],
            _ => &["--method", "fem", "--elements", "32"],
        };
        let mut args = vec!["solve", scene.to_str().unwrap(), "--fields", "16", "--json", out.to_str().unwrap()];
        args.extend_from_slice(method);
        let label = format!("{} ({what}) {method:?}", scenes[k]);
        let Some(o) = run_bounded(&args) else {
            stopped += 1;
            let _ = std::fs::remove_file(&out);
            continue;
        };
        let (so, se) = (common::stdout(&o), common::stderr(&o));
        assert!(!se.contains("panicked"), "{label}: {se}");
        match o.status.code() {
            Some(0) => {
                ok += 1;
                no_nan(&label, &so);
                let result = std::fs::read_to_string(&out).unwrap_or_else(|_| panic!("{label}: exit 0 without a result"));
                no_nan(&label, &result);
                let v: serde_json::Value = serde_json::from_str(&result).expect("valid JSON");
                let mut nums = Vec::new();
                numbers(&v["summary"], String::new(), &mut nums);
                assert!(!nums.is_empty(), "{label}: empty summary");
                for block in ["summary", "fields", "cost"] {
                    assert!(!v[block].to_string().contains("null"), "{label}: a null (non-finite) in `{block}`");
                }
            }
            Some(2) => {
                refused += 1;
                assert!(se.starts_with("error: "), "{label}: {se}");
                assert!(!out.exists(), "{label}: a result was written on exit 2");
            }
            other => panic!("{label}: exit status {other:?}\n{so}\n{se}"),
        }
        let partials: Vec<_> = std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()).filter(|e| e.file_name().to_string_lossy().ends_with(".partial")).collect();
        assert!(partials.is_empty(), "{label}: temporary file left");
    }
    eprintln!("cli fuzz: {ok} solved, {refused} refused, {stopped} stopped after {RUN_LIMIT:?}, {:.1} s", start.elapsed().as_secs_f64());
    assert!(ok + refused >= 10, "too few cases judged: {ok} solved, {refused} refused, {stopped} stopped");
    assert!(ok > 0 && refused > 0, "the mutations must give both outcomes: {ok} solved, {refused} refused");
}
