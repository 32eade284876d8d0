//! The city view's server side through the router (no socket): folders opened at start, each
//! listed with its epochs or with why it cannot be shown, its files served by their listed
//! paths only, and what stops the server at start. The page itself is driven in a real browser
//! by `tests/web/city.mjs`.

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use sylva_city::tasks::{SUMMARY_FORMAT, SUMMARY_GENERATOR};
use sylva_serve::city::Cities;
use sylva_serve::{Options, State, router};
use tower::ServiceExt;

/// A folder laid out as `sylva city` lays one out at epochs 0 and 10 (the tiles' content is
/// only bytes: the server never reads it).
fn city(root: &Path, name: &str) -> PathBuf {
    let dir = root.join(name);
    for years in [0, 10] {
        let tiles = dir.join(format!("year-{years}/content/0"));
        std::fs::create_dir_all(&tiles).unwrap();
        std::fs::write(tiles.join("0-0.glb"), b"glTF tile").unwrap();
        std::fs::write(
            dir.join(format!("year-{years}/tileset.json")),
            r#"{"asset":{"version":"1.1","generator":"Sylva 0.1.0"},"geometricError":1,"root":{}}"#,
        )
        .unwrap();
    }
    summary(&dir, SUMMARY_GENERATOR, SUMMARY_FORMAT);
    std::fs::write(dir.join("report.json"), "{}").unwrap();
    dir
}

fn summary(dir: &Path, generator: &str, format: u32) {
    let s = serde_json::json!({
        "generator": generator, "format": format, "version": "0.1.0",
        "origin": { "longitude": -121.0, "latitude": 37.6 }, "rows": 3, "trees": 2,
        "epochs": [
            { "years": 0, "tileset": "year-0/tileset.json", "trees": 2 },
            { "years": 10, "tileset": "year-10/tileset.json", "trees": 2 },
        ],
    });
    std::fs::write(dir.join("summary.json"), s.to_string()).unwrap();
}

async fn get(state: &Arc<State>, uri: &str, tag: Option<&str>) -> (StatusCode, Vec<u8>, String) {
    let mut request = Request::get(uri);
    if let Some(t) = tag {
        request = request.header("if-none-match", t);
    }
    let response = router(state.clone())
        .oneshot(request.body(Body::empty()).unwrap())
        .await
        .unwrap();
    let status = response.status();
    let etag = response
        .headers()
        .get("etag")
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let body = response.into_body().collect().await.unwrap().to_bytes();
    (status, body.to_vec(), etag)
}

#[tokio::test]
async fn a_city_is_listed_and_only_its_listed_files_are_served() {
    let root = tempfile::tempdir().unwrap();
    let good = city(root.path(), "modesto");
    // What must never be served: a hidden staging folder's file, and a link out of the folder.
    std::fs::create_dir_all(good.join(".modesto.sylva-123")).unwrap();
    std::fs::write(good.join(".modesto.sylva-123/secret"), "staging").unwrap();
    let outside = root.path().join("outside.txt");
    std::fs::write(&outside, "not the city's").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(&outside, good.join("link.txt")).unwrap();
    let empty = root.path().join("photos");
    std::fs::create_dir(&empty).unwrap();
    let damaged = city(root.path(), "damaged");
    std::fs::write(damaged.join("summary.json"), "{\"epochs\": [").unwrap();
    let other = city(root.path(), "other");
    summary(&other, "py3dtiles", 1);
    let old = city(root.path(), "old");
    summary(&old, SUMMARY_GENERATOR, SUMMARY_FORMAT + 1);
    let torn = city(root.path(), "torn");
    std::fs::remove_file(torn.join("year-10/tileset.json")).unwrap();

    let cities = Cities::open(&[good, empty, damaged, other, old, torn], None).unwrap();
    let state = State::with_cities(
        &Options {
            warm: Vec::new(),
            ..Default::default()
        },
        cities,
    );
    let (status, body, _) = get(&state, "/api/cities", None).await;
    assert_eq!(status, StatusCode::OK);
    let listed: serde_json::Value = serde_json::from_slice(&body).unwrap();
    let by = |name: &str| {
        listed["cities"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["name"] == name)
            .unwrap()
            .clone()
    };
    let m = by("modesto");
    assert!(m["problem"].is_null(), "{m}");
    assert_eq!(m["epochs"][1]["years"], 10);
    assert_eq!(
        m["epochs"][1]["tileset"],
        "/city/modesto/year-10/tileset.json"
    );
    assert_eq!(m["report"]["json"], "/city/modesto/report.json");
    assert!(m["report"]["html"].is_null(), "no report.html was written");
    assert_eq!(listed["dbh_class_edges_cm"].as_array().unwrap().len(), 8);
    for (name, why) in [
        ("photos", "no summary.json"),
        ("damaged", "summary.json is damaged"),
        ("other", "written by `py3dtiles`"),
        ("old", "this sylva reads format"),
        ("torn", "year-10/tileset.json is missing"),
    ] {
        let problem = by(name)["problem"].as_str().unwrap_or("").to_string();
        assert!(problem.contains(why), "{name}: {problem}");
        assert!(by(name)["epochs"].as_array().unwrap().is_empty());
    }

    let (status, body, tag) = get(&state, "/city/modesto/year-0/content/0/0-0.glb", None).await;
    assert_eq!(
        (status, body.as_slice()),
        (StatusCode::OK, &b"glTF tile"[..])
    );
    // Asked again with its tag: not sent again.
    let (status, body, _) = get(&state, "/city/modesto/year-0/content/0/0-0.glb", Some(&tag)).await;
    assert_eq!(status, StatusCode::NOT_MODIFIED);
    assert!(body.is_empty());
    for path in [
        "/city/modesto/../outside.txt",
        "/city/modesto/%2e%2e/outside.txt",
        "/city/modesto/year-0/../../outside.txt",
        "/city/modesto//etc/passwd",
        "/city/modesto/%2Fetc%2Fpasswd",
        "/city/modesto/link.txt",
        "/city/modesto/.modesto.sylva-123/secret",
        "/city/photos/summary.json",
        "/city/damaged/summary.json",
        "/city/nowhere/summary.json",
    ] {
        let (status, body, _) = get(&state, path, None).await;
        assert_eq!(status, StatusCode::NOT_FOUND, "{path}");
        assert!(
            String::from_utf8_lossy(&body).contains("not found"),
            "{path}"
        );
    }
}

#[test]
fn what_cannot_be_a_city_stops_the_server_at_start() {
    let root = tempfile::tempdir().unwrap();
    let a = city(root.path(), "same");
    std::fs::create_dir(root.path().join("b")).unwrap();
    let b = city(&root.path().join("b"), "same");
    let refused = |dirs: &[PathBuf], basemap: Option<&str>| {
        Cities::open(dirs, basemap.map(str::to_string))
            .err()
            .map(|e| e.0)
            .unwrap_or_default()
    };
    let twins = refused(&[a.clone(), b], None);
    assert!(twins.contains("two cities named `same`"), "{twins}");
    let missing = refused(&[root.path().join("nowhere")], None);
    assert!(
        missing.starts_with("--city ") && missing.contains("nowhere"),
        "{missing}"
    );
    let file = refused(&[a.join("summary.json")], None);
    assert!(file.contains("not a folder"), "{file}");
    let basemap = refused(
        std::slice::from_ref(&a),
        Some("https://tile.example.org/{z}/{x}.png"),
    );
    assert!(
        basemap.contains("--basemap") && basemap.contains("{y}"),
        "{basemap}"
    );
    let scheme = refused(std::slice::from_ref(&a), Some("file:///{z}/{x}/{y}.png"));
    assert!(scheme.contains("http"), "{scheme}");
    assert!(Cities::open(&[a], Some("https://t.example.org/{z}/{x}/{y}.png".into())).is_ok());
}
