//! One output shape: the same request gives the same records from `sylva grow --json` and
//! from the planners' page's API (`sylva serve`, `/api/growth`).

use crate::{json_lines, text};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};

/// `sylva serve` on a free port, stopped when dropped.
struct Server {
    child: Child,
    address: String,
}

impl Server {
    fn start() -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_sylva"))
            .args(["serve", "--port", "0"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("starts sylva serve");
        // It says where the page is once it listens: `... the page is at http://HOST:PORT/`.
        let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
        let address = loop {
            let line = lines
                .next()
                .expect("sylva serve says where it listens")
                .unwrap();
            if let Some(url) = line.split("the page is at http://").nth(1) {
                break url.split('/').next().unwrap().to_string();
            }
        };
        Server { child, address }
    }

    /// The body of a GET that must answer 200, asked again as a 503 says (`Retry-After`:
    /// the server is busy growing, or its memory bound is full until growths end), for at
    /// most five minutes.
    fn get(&self, path: &str) -> String {
        let until = std::time::Instant::now() + std::time::Duration::from_secs(300);
        loop {
            let mut stream = TcpStream::connect(&self.address).unwrap();
            write!(
                stream,
                "GET {path} HTTP/1.1\r\nHost: {}\r\nConnection: close\r\n\r\n",
                self.address
            )
            .unwrap();
            let mut answer = Vec::new();
            stream.read_to_end(&mut answer).unwrap();
            let answer = text(&answer);
            let (head, body) = answer.split_once("\r\n\r\n").unwrap();
            let retry = (head.lines())
                .find_map(|l| {
                    l.to_ascii_lowercase()
                        .strip_prefix("retry-after: ")
                        .map(str::to_owned)
                })
                .and_then(|s| s.trim().parse::<u64>().ok());
            if let (true, Some(seconds)) = (head.starts_with("HTTP/1.1 503"), retry)
                && std::time::Instant::now() < until
            {
                std::thread::sleep(std::time::Duration::from_secs(seconds));
                continue;
            }
            assert!(head.starts_with("HTTP/1.1 200"), "{path}: {head}\n{body}");
            assert!(!head.to_ascii_lowercase().contains("chunked"), "{head}");
            return body.to_string();
        }
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A plane on the narrow site under wires, pruned by its regime, ages 1 to 14: the CLI's
/// `street` record of each age is the page's, field for field, and the grown dimensions are
/// the same tree's (the page rounds them coarser). Both grow through the library's study
/// pipeline; this holds their requests, records and rounding together.
#[test]
fn grow_json_and_the_pages_api_give_the_same_records() {
    let site = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../sites/narrow-under-wires.toml"
    );
    let out = tempfile::tempdir().unwrap();
    let o = out.path().to_str().unwrap();
    let cli = json_lines(&[
        "grow",
        "PLAC",
        "--region",
        "InlVal",
        "--from",
        "1",
        "--to",
        "14",
        "--site",
        site,
        "--no-pictures",
        "--json",
        "-o",
        o,
    ]);
    assert_eq!(cli.len(), 14);
    let server = Server::start();
    let page: serde_json::Value = serde_json::from_str(
        &server.get("/api/growth?region=InlVal&species=PLAC&site=narrow&pruning=on"),
    )
    .unwrap();
    let rows = page["rows"].as_array().unwrap();
    assert!(rows.len() >= 14, "{} ages on the page", rows.len());
    let mut pruned = 0;
    for line in &cli {
        let age = line["age"].as_f64().unwrap();
        let row = rows.iter().find(|r| r["age"] == age).unwrap();
        assert_eq!(
            line["street"], row["street"],
            "age {age}: the year's account"
        );
        pruned += usize::from(!line["street"]["pruning"].is_null());
        for (cli_key, page_key, places) in [
            ("height_m", "height", 2),
            ("crown_diameter_m", "crown_diameter", 2),
            ("dbh_cm", "dbh", 1),
            ("leaf_area_m2", "leaf_area", 1),
        ] {
            let k = 10f64.powi(places);
            let grown = (line[cli_key].as_f64().unwrap() * k).round() / k;
            let shown = row["model"][page_key].as_f64().unwrap();
            // The CLI's figure is itself rounded finer: the two roundings meet within a step.
            assert!(
                (grown - shown).abs() <= 1.0 / k + 1e-9,
                "age {age}: {cli_key} {grown} on the CLI, {page_key} {shown} on the page"
            );
        }
    }
    // The regime cut the tree in some of these years: the pruning records were compared too.
    assert!(pruned > 0, "no pruning in ages 1 to 14");
    // Both read the same record type: every field the CLI writes, the page writes.
    let keys =
        |v: &serde_json::Value| -> Vec<String> { v.as_object().unwrap().keys().cloned().collect() };
    assert_eq!(keys(&cli[13]["street"]), keys(&rows[13]["street"]));
}
