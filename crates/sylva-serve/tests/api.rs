//! The API as a client sees it, through the router (no socket): answers read back by real
//! readers (the gltf crate, image, JSON), bad parameters refused with 400 and a message naming
//! them, nothing but the page's files served, identical requests grown once.

use axum::body::Body;
use axum::http::{Request, StatusCode};
use http_body_util::BodyExt;
use std::sync::Arc;
use sylva_serve::{Options, State, router};
use tower::ServiceExt;

/// A state whose requests wait as long as growths take: the tests run beside others on a
/// shared machine, where a growth may take longer than the server's 30 s.
fn state() -> Arc<State> {
    State::new(&Options {
        warm: Vec::new(),
        wait_limit: std::time::Duration::from_secs(600),
        ..Default::default()
    })
}

async fn get(state: &Arc<State>, uri: &str) -> (StatusCode, String, Vec<u8>) {
    let response = router(state.clone())
        .oneshot(Request::get(uri).body(Body::empty()).unwrap())
        .await
        .unwrap();
    let status = response.status();
    let kind = response
        .headers()
        .get("content-type")
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let body = response.into_body().collect().await.unwrap().to_bytes();
    (status, kind, body.to_vec())
}

async fn json(state: &Arc<State>, uri: &str) -> serde_json::Value {
    let (status, kind, body) = get(state, uri).await;
    assert_eq!(
        status,
        StatusCode::OK,
        "{uri}: {}",
        String::from_utf8_lossy(&body)
    );
    assert!(kind.starts_with("application/json"), "{uri}: {kind}");
    serde_json::from_slice(&body).unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn regions_and_species_list_the_database() {
    let s = state();
    let regions = json(&s, "/api/regions").await;
    let regions = regions.as_array().unwrap();
    assert_eq!(regions.len(), 17, "the Urban Tree Database's 17 regions");
    assert_eq!(regions[0]["code"], "InlVal", "Modesto first");
    assert_eq!(regions[0]["city"], "Modesto");
    assert!((regions[0]["latitude"].as_f64().unwrap() - 37.6).abs() < 0.1);
    let species = json(&s, "/api/species?region=InlVal").await;
    let species = species.as_array().unwrap();
    assert_eq!(
        species.len(),
        regions[0]["species"].as_u64().unwrap() as usize
    );
    let plane = species.iter().find(|x| x["code"] == "PLAC").unwrap();
    assert_eq!(plane["common"], "London planetree");
    let ages = plane["ages"].as_array().unwrap();
    assert!(ages[0].as_u64().unwrap() <= 5 && ages[1].as_u64().unwrap() >= 50);
    let sites = json(&s, "/api/sites").await;
    assert_eq!(sites.as_array().unwrap().len(), 3);
    assert_eq!(sites[0]["site"]["wire"][0]["height"], 8.5);
}

/// The page's charts draw every item of the library's one table of account items: the API
/// serves the table whole, and `charts.js` names no item itself, so an item added to the
/// table is drawn and keyed without touching the page.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_draws_every_account_item_from_the_one_table() {
    use sylva::street::accounts::items;
    let s = state();
    let served = json(&s, "/api/items").await;
    let served = served.as_array().unwrap();
    let table: Vec<_> = items::all().collect();
    assert_eq!(served.len(), table.len());
    for (row, item) in served.iter().zip(&table) {
        assert_eq!(row["key"], item.key);
        assert_eq!(row["label"], item.label);
        assert_eq!(row["colour"], item.colour);
        assert_eq!(row["unit"], item.unit);
        match item.payer {
            Some(p) => assert_eq!(row["payer"], p.name()),
            None => assert!(row["payer"].is_null()),
        }
    }
    let (status, _, charts) = get(&s, "/charts.js").await;
    assert_eq!(status, StatusCode::OK);
    let charts = String::from_utf8(charts).unwrap();
    assert!(charts.contains("'/api/items'"), "charts.js reads the table");
    for item in &table {
        assert!(
            !charts.contains(&format!("'{}'", item.key)),
            "charts.js names `{}` itself: it must come from /api/items",
            item.key
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_grown_tree_comes_back_as_a_readable_glb_of_its_measured_height() {
    let s = state();
    let (status, kind, glb) = get(&s, "/api/tree.glb?region=InlVal&species=LAIN&age=6").await;
    assert_eq!(status, StatusCode::OK, "{}", String::from_utf8_lossy(&glb));
    assert_eq!(kind, "model/gltf-binary");
    let gltf = gltf::Gltf::from_slice(&glb).expect("a GLB the gltf crate reads");
    let mesh = gltf.meshes().next().unwrap();
    assert_eq!(mesh.primitives().count(), 2, "bark and leaves");
    let top = mesh
        .primitives()
        .map(|p| p.bounding_box().max[1])
        .fold(0.0f32, f32::max);
    let growth = json(&s, "/api/growth?region=InlVal&species=LAIN").await;
    let row = growth["rows"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["age"] == 6.0)
        .unwrap()
        .clone();
    let height = row["model"]["height"].as_f64().unwrap() as f32;
    assert!(
        (top - height).abs() < 0.05,
        "GLB top {top} m, grown height {height} m"
    );
    let measured = row["measured"]["height"].as_f64().unwrap() as f32;
    assert!(
        (height / measured - 1.0).abs() < 0.1,
        "{height} vs {measured} m"
    );
    // The year's account is there with the typical position beside it, and what is not
    // computed says so.
    assert!(row["street"]["co2_stored_kg"].as_f64().unwrap() > 0.0);
    assert!(
        row["street"]["typical"]["value_usd"]["air_quality"]
            .as_f64()
            .unwrap()
            > 0.0
    );
    assert!(row["street"]["typical"]["net_usd"].is_f64());
    // Aesthetics are priced (McPherson 2007's method); the cost items no source gives are
    // listed as not computed.
    assert!(
        row["street"]["typical"]["value_usd"]["aesthetics"]
            .as_f64()
            .unwrap()
            >= 0.0
    );
    assert!(growth["missing"].as_array().unwrap().iter().any(|m| {
        m.as_str()
            .unwrap()
            .starts_with("costs of clean-up, pest management")
    }));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn downloads_csv_svg_and_png_read_back() {
    let s = state();
    let (status, kind, csv) = get(&s, "/api/table.csv?species=LAIN,PRCE&site=boulevard").await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(kind, "text/csv");
    let text = String::from_utf8(csv).unwrap();
    let mut reader = csv_rows(&text);
    let header = reader.remove(0);
    assert_eq!(header[0], "species");
    assert!(header.iter().any(|h| h == "net_usd"), "{header:?}");
    assert!(reader.iter().any(|r| r[0] == "LAIN") && reader.iter().any(|r| r[0] == "PRCE"));
    assert!(reader.iter().all(|r| r.len() == header.len()));
    let (status, kind, svg) = get(&s, "/api/plan.svg?species=LAIN&age=8").await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(kind, "image/svg+xml");
    let svg = String::from_utf8(svg).unwrap();
    assert!(
        svg.starts_with("<svg") || svg.starts_with("<?xml"),
        "{}",
        &svg[..60]
    );
    assert!(svg.contains("<path") || svg.contains("<line") || svg.contains("<polyline"));
    let (status, kind, png) =
        get(&s, "/api/compare.png?species=LAIN,PRCE&age=8&size=320x200").await;
    assert_eq!(status, StatusCode::OK, "{}", String::from_utf8_lossy(&png));
    assert_eq!(kind, "image/png");
    let picture = image::load_from_memory(&png).unwrap();
    assert_eq!(picture.width(), 320);
    assert!(picture.height() > 200, "a caption under the picture");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_site_picture_marks_a_conflict() {
    let s = state();
    // A crapemyrtle of 8 years on the narrow site is over the sidewalk's clearance.
    let growth = json(&s, "/api/growth?species=LAIN&site=narrow").await;
    let row = &growth["rows"].as_array().unwrap()[7];
    assert_eq!(row["age"], 8.0);
    assert!(
        !row["street"]["conflicts"].as_array().unwrap().is_empty(),
        "{row}"
    );
    let (status, kind, png) = get(&s, "/api/site.png?species=LAIN&age=8&site=narrow").await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(kind, "image/png");
    let picture = image::load_from_memory(&png).unwrap().to_rgba8();
    assert_eq!(picture.dimensions(), (640, 300));
    let red = picture
        .pixels()
        .filter(|p| p[0] > 180 && p[1] < 90 && p[2] < 90)
        .count();
    assert!(red > 20, "{red} red pixels");
}

fn csv_rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_parameters_get_400_naming_them() {
    let s = state();
    let cases = [
        ("/api/species?region=Atlantis", "region"),
        ("/api/growth?species=NOPE", "species"),
        ("/api/growth", "species"),
        ("/api/tree.glb?species=LAIN&age=500", "age"),
        ("/api/tree.glb?species=LAIN&age=ten", "age"),
        ("/api/tree.glb?species=LAIN&age=2.5", "age"),
        ("/api/tree.glb?species=LAIN", "age"),
        ("/api/tree.glb?species=LAIN&age=5&seed=-1", "seed"),
        ("/api/growth?species=LAIN&site=roof", "site"),
        (
            "/api/compare.png?species=LAIN,PRCE,PLAC,PICH,ZESE&age=5",
            "species",
        ),
        ("/api/compare.png?species=LAIN&age=5&size=9x9", "size"),
        ("/api/tree.glb?species=LAIN,PRCE&age=5", "species"),
        ("/api/tree.glb?species=LAIN&age=5&detail=5", "detail"),
        ("/api/growth?species=LAIN&pruning=sometimes", "pruning"),
        (
            "/api/tree.glb?species=LAIN&age=5&pruning=on&site=roof",
            "site",
        ),
    ];
    for (uri, parameter) in cases {
        let (status, kind, body) = get(&s, uri).await;
        assert_eq!(status, StatusCode::BAD_REQUEST, "{uri}");
        assert!(kind.starts_with("application/json"), "{uri}");
        let body: serde_json::Value = serde_json::from_slice(&body).unwrap();
        assert_eq!(body["parameter"], parameter, "{uri}: {body}");
        let error = body["error"].as_str().unwrap();
        assert!(
            error.starts_with(&format!("{parameter}: ")),
            "{uri}: {error}"
        );
        assert!(!body["allowed"].as_str().unwrap().is_empty(), "{uri}");
    }
    assert!(s.cache.is_empty(), "nothing grew for a bad request");
}

#[tokio::test]
async fn only_the_page_files_are_served() {
    let s = state();
    let (status, kind, body) = get(&s, "/").await;
    assert_eq!(status, StatusCode::OK);
    assert!(kind.starts_with("text/html"));
    assert!(String::from_utf8(body).unwrap().contains("/app.js"));
    let (status, kind, _) = get(&s, "/vendor/three.min.js").await;
    assert_eq!(status, StatusCode::OK);
    assert!(kind.starts_with("text/javascript"));
    for uri in [
        "/../Cargo.toml",
        "/%2e%2e/Cargo.toml",
        "/..%2fCargo.toml",
        "//etc/passwd",
        "/vendor/../app.js",
        "/assets/app.js",
        "/src/lib.rs",
        "/api/nothing",
    ] {
        let (status, _, _) = get(&s, uri).await;
        assert_eq!(status, StatusCode::NOT_FOUND, "{uri}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn identical_requests_in_flight_are_grown_once() {
    let s = state();
    let requests: Vec<_> = (0..8)
        .map(|_| {
            let s = s.clone();
            tokio::spawn(async move { get(&s, "/api/growth?species=LAIN&seed=7").await })
        })
        .collect();
    let mut bodies = Vec::new();
    for r in requests {
        let (status, _, body) = r.await.unwrap();
        assert_eq!(status, StatusCode::OK);
        bodies.push(body);
    }
    assert_eq!(s.cache.len(), 1, "one growth for eight requests");
    assert!(bodies.windows(2).all(|w| w[0] == w[1]));
    let status = json(&s, "/api/status").await;
    assert_eq!(status["growths"], 1);
    // Every byte kept is the growth's ages and the answer kept for asking again.
    let bytes = |k: &str| status[k].as_u64().unwrap();
    assert!(bytes("growth_bytes") > 0);
    assert_eq!(
        bytes("cache_bytes"),
        bytes("growth_bytes") + bytes("recent_bytes")
    );
    assert_eq!(bytes("growth_bytes"), bytes("held_bytes"));
    assert!(bytes("cache_bytes") <= bytes("cache_bound"));
    assert_eq!(status["growing"], 0);
}

/// A server whose bound cannot hold a species stops its growth at the bound and says so:
/// first 503 with a time to ask again (the growth was tried: a first guess cannot know), then
/// 507 naming the `--cache-mib` that would hold it; the bound is never passed.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_species_larger_than_the_bound_is_refused_with_what_would_hold_it() {
    let s = State::new(&Options {
        warm: Vec::new(),
        cache_bytes: 64 << 20,
        // The bound, not the wait, must end the first request, however loaded the machine.
        wait_limit: std::time::Duration::from_secs(600),
        ..Default::default()
    });
    let response = router(s.clone())
        .oneshot(
            Request::get("/api/growth?species=PRCE")
                .body(Body::empty())
                .unwrap(),
        )
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::SERVICE_UNAVAILABLE);
    let retry = response.headers().get("retry-after").unwrap();
    assert_eq!(retry.to_str().unwrap(), "2");
    let body = response.into_body().collect().await.unwrap().to_bytes();
    let body: serde_json::Value = serde_json::from_slice(&body).unwrap();
    let said = body["error"].as_str().unwrap();
    assert!(
        said.contains("stopped") && said.contains("memory bound"),
        "{said}"
    );
    assert_eq!(body["retry_after"], 2);
    let (status, _, body) = get(&s, "/api/growth?species=PRCE").await;
    let said = String::from_utf8_lossy(&body);
    assert_eq!(status, StatusCode::INSUFFICIENT_STORAGE, "{said}");
    assert!(said.contains("--cache-mib"), "{said}");
    let status = json(&s, "/api/status").await;
    assert!(status["cache_bytes"].as_u64() <= status["cache_bound"].as_u64());
    assert_eq!(status["refused"]["stopped"], 1);
    assert_eq!(status["refused"]["too_large"], 1);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn hostile_values_are_refused_never_a_panic() {
    let s = state();
    let long = "9".repeat(5000);
    let values = [
        "",
        " ",
        "-1",
        "NaN",
        "inf",
        "-inf",
        "1e309",
        "0x10",
        "1.0e1",
        "%00",
        "%ff%fe",
        "☃",
        "../../etc",
        "PLAC,",
        ",",
        ",,,,",
        long.as_str(),
    ];
    for value in values {
        for parameter in ["region", "species", "age", "seed", "site", "size", "detail"] {
            let mut query = vec![("species", "LAIN"), ("age", "200")];
            query.retain(|(k, _)| *k != parameter);
            query.push((parameter, value));
            let q: Vec<String> = query
                .iter()
                .map(|(k, v)| format!("{k}={}", v.replace(' ', "%20")))
                .collect();
            for path in [
                "tree.glb",
                "growth",
                "compare.png",
                "plan.svg",
                "table.csv",
                "site.png",
            ] {
                let uri = format!("/api/{path}?{}", q.join("&"));
                let (status, _, body) = get(&s, &uri).await;
                assert!(
                    status == StatusCode::BAD_REQUEST || status == StatusCode::OK,
                    "{uri}: {status}"
                );
                if status == StatusCode::BAD_REQUEST {
                    let body: serde_json::Value = serde_json::from_slice(&body).unwrap();
                    assert!(body["error"].as_str().unwrap().contains(':'), "{uri}");
                }
            }
        }
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn pruning_on_cuts_the_tree_for_its_site_and_charges_the_cycles() {
    let s = state();
    let uri = "/api/growth?species=PLAC&site=narrow";
    let cut = json(&s, &format!("{uri}&pruning=on")).await;
    let grown = json(&s, uri).await;
    assert_eq!(
        (cut["pruning"].as_bool(), grown["pruning"].as_bool()),
        (Some(true), Some(false))
    );
    let rows = |g: &serde_json::Value| g["rows"].as_array().unwrap().clone();
    let (cut, grown) = (rows(&cut), rows(&grown));
    assert_eq!(cut.len(), grown.len());
    // The utility clears the wire at 8, for its clearance and the regrowth before its next
    // visit: the cut tree has the cycle, its cost and the line's check, and never a leaf or
    // wood inside the line's minimum; the tree never cut has none of these and runs into the
    // wire.
    let at = |rows: &[serde_json::Value], age: f64| {
        rows.iter().find(|r| r["age"] == age).unwrap()["street"].clone()
    };
    let (c8, g8) = (at(&cut, 8.0), at(&grown, 8.0));
    let pruning = &c8["pruning"];
    assert!(
        pruning["reasons"]
            .as_array()
            .unwrap()
            .iter()
            .any(|r| r == "line clearance"),
        "{c8}"
    );
    let line = &c8["lines"][0];
    assert!(
        line["visit"]["scheduled"] == true && line["breach"] == false,
        "{c8}"
    );
    assert!(
        (cut.iter()).all(|r| r["street"]["lines"]
            .as_array()
            .unwrap()
            .iter()
            .all(|l| l["breach"] == false)),
        "no breach at any age"
    );
    // Line clearance is the utility's to pay: charged to the tree, apart from the city's.
    assert!(
        c8["cost_usd"]["line_clearance_utility"].as_f64().unwrap() > 0.0,
        "{c8}"
    );
    assert!(
        g8["pruning"].is_null()
            && g8["cost_usd"]["cycles"] == 0.0
            && g8["cost_usd"]["line_clearance_utility"] == 0.0,
        "{g8}"
    );
    let wire = |st: &serde_json::Value| {
        st["conflicts"]
            .as_array()
            .unwrap()
            .iter()
            .any(|c| c["kind"] == "wire")
    };
    assert!(!wire(&c8) && wire(&g8));
    // Both growths are held, one apart from the other.
    assert_eq!(s.cache.len(), 2);
    // The cut tree's GLB is its own.
    let (status, _, cut_glb) = get(
        &s,
        "/api/tree.glb?species=PLAC&age=8&site=narrow&pruning=on",
    )
    .await;
    assert_eq!(status, StatusCode::OK);
    let (_, _, grown_glb) = get(&s, "/api/tree.glb?species=PLAC&age=8").await;
    assert_ne!(cut_glb, grown_glb);
}
