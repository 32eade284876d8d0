//! The page's own files, compiled into the binary: nothing is fetched from the internet, and
//! nothing but these is served. A path is looked up in this fixed table and never joined to a
//! folder, so `..`, absolute paths and anything else not listed get 404.

use axum::http::{StatusCode, Uri, header};
use axum::response::{IntoResponse, Response};

/// Path, content type, bytes.
const FILES: &[(&str, &str, &[u8])] = &[
    (
        "/",
        "text/html; charset=utf-8",
        include_bytes!("../assets/index.html"),
    ),
    (
        "/style.css",
        "text/css; charset=utf-8",
        include_bytes!("../assets/style.css"),
    ),
    (
        "/app.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/app.js"),
    ),
    (
        "/scene.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/scene.js"),
    ),
    (
        "/charts.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/charts.js"),
    ),
    (
        "/ask.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/ask.js"),
    ),
    (
        "/city.html",
        "text/html; charset=utf-8",
        include_bytes!("../assets/city.html"),
    ),
    (
        "/city.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/city.js"),
    ),
    (
        "/gl.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/gl.js"),
    ),
    (
        "/city-ground.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/city-ground.js"),
    ),
    (
        "/city-report.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/city-report.js"),
    ),
    (
        "/city-trees.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/city-trees.js"),
    ),
    (
        "/vendor/city.min.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/vendor/city.min.js"),
    ),
    (
        "/vendor/3d-tiles-renderer-LICENSE.txt",
        "text/plain; charset=utf-8",
        include_bytes!("../assets/vendor/3d-tiles-renderer-LICENSE.txt"),
    ),
    (
        "/vendor/three.min.js",
        "text/javascript; charset=utf-8",
        include_bytes!("../assets/vendor/three.min.js"),
    ),
    (
        "/vendor/three-LICENSE.txt",
        "text/plain; charset=utf-8",
        include_bytes!("../assets/vendor/three-LICENSE.txt"),
    ),
];

/// The file at `path`, if the page has one there.
pub fn find(path: &str) -> Option<(&'static str, &'static [u8])> {
    let path = if path == "/index.html" { "/" } else { path };
    FILES
        .iter()
        .find(|(p, _, _)| *p == path)
        .map(|&(_, kind, bytes)| (kind, bytes))
}

/// Serves a page file, or 404.
pub async fn serve(uri: Uri) -> Response {
    match find(uri.path()) {
        Some((kind, bytes)) => ([(header::CONTENT_TYPE, kind)], bytes).into_response(),
        None => (
            StatusCode::NOT_FOUND,
            [(header::CONTENT_TYPE, "application/json")],
            serde_json::json!({"error": format!("{}: not found", uri.path())}).to_string(),
        )
            .into_response(),
    }
}
