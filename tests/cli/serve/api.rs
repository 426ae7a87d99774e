//! The JSON API of `fair serve`: each endpoint against the command's own output, every bad
//! request answered 4xx with a message (the server living on), 50 concurrent requests
//! answered as sequential ones are.

use super::client::{get, post, raw, request};
use super::{bits, command_report, file_bits, root, scratch, untimed, Served};
use serde_json::{json, Value};

const WL03: &str = "data/hull_gunnerus/waterlines/wl_03.csv";
const TEAPOT: &str = "data/surface_utah_teapot/teapot_body_control_net.csv";

fn file(path: &str) -> String {
    root().join(path).display().to_string()
}

#[test]
fn page_and_assets_are_served_from_the_binary_only() {
    let server = Served::start(&[]);
    let page = get(&server.address, "/");
    assert_eq!(page.status, 200);
    assert_eq!(page.header("Content-Type"), Some("text/html; charset=utf-8"));
    let csp = page
        .header("Content-Security-Policy")
        .expect("a content security policy");
    assert!(
        csp.contains("script-src 'self'") && csp.contains("connect-src 'self'"),
        "{csp}"
    );
    let html = String::from_utf8(page.body.clone()).unwrap();
    assert!(html.contains(r#"<script src="app.js""#) && html.contains(r#"href="style.css""#));
    for (path, kind) in [("/app.js", "text/javascript"), ("/style.css", "text/css")] {
        let asset = get(&server.address, path);
        assert_eq!(asset.status, 200, "{path}");
        assert!(asset.header("Content-Type").unwrap().starts_with(kind), "{path}");
        let text = String::from_utf8(asset.body).unwrap();
        // Nothing is loaded from elsewhere: no address but the SVG namespace.
        let outside = text.replace("http://www.w3.org/2000/svg", "");
        assert!(
            !outside.contains("http://") && !outside.contains("https://"),
            "{path} reaches out"
        );
    }
    assert!(!html.contains("http://") && !html.contains("https://"));
}

/// The page's corners control: a field `corners` (with the words `auto` and `none` offered)
/// whose value the page's `constraints()` sends as `constraints.corners`, as `--corners`
/// takes it: empty sends nothing (the default), `auto` and `none` as words, else the point
/// indices. Where node is on the PATH, the page's own parsing runs on typed values and the
/// API takes what it builds (a word outside auto/none is refused with the API's message).
#[test]
fn the_page_sends_the_corners_control_as_constraints_corners() {
    let server = Served::start(&[]);
    let html = String::from_utf8(get(&server.address, "/").body).unwrap();
    assert!(html.contains(r#"<input id="corners""#), "no corners field");
    assert!(
        html.contains(r#"<option value="auto">"#) && html.contains(r#"<option value="none">"#),
        "the words are not offered"
    );
    let script = String::from_utf8(get(&server.address, "/app.js").body).unwrap();
    let start = script.find("function constraints(").expect("constraints()");
    let body = &script[start..start + script[start..].find("\n  }\n").unwrap()];
    assert!(
        body.contains(r#"cornersOf($("corners").value)"#) && body.contains("c.corners = corners"),
        "constraints() does not send the field: {body}"
    );
    let Some(node) = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join("node"))
            .find(|path| path.is_file())
    }) else {
        eprintln!("skipping the page's corner parsing: node is not on the PATH");
        return;
    };
    let start = script.find("function cornersOf(").expect("cornersOf()");
    let function = &script[start..start + script[start..].find("\n  }\n").unwrap() + 4];
    let typed = ["", "  ", "auto", " None ", "20, 40", "20 40,", "often"];
    let program = format!(
        "{function}\nconsole.log(JSON.stringify({}.map(cornersOf)));",
        serde_json::to_string(&typed).unwrap()
    );
    let out = std::process::Command::new(node)
        .args(["-e", &program])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let sent: Vec<Value> = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        sent,
        [
            Value::Null,
            Value::Null,
            json!("auto"),
            json!("none"),
            json!([20, 40]),
            json!([20, 40]),
            json!(["often"]),
        ]
    );
    let points = get(&server.address, "/api/datasets/gunnerus-wl03").json()["points"].clone();
    for corners in &sent[2..] {
        let body = json!({ "points": points, "constraints": { "corners": corners } });
        let reply = post(&server.address, "/api/curve", &body.to_string());
        if corners == &json!(["often"]) {
            assert_eq!(reply.status, 400, "{corners}");
            assert!(reply.error().contains("constraints.corners"), "{}", reply.error());
        } else {
            assert_eq!(reply.status, 200, "{corners}: {}", reply.error());
        }
    }
}

#[test]
fn methods_are_the_catalogue_with_defaults() {
    let server = Served::start(&[]);
    let reply = get(&server.address, "/api/methods");
    assert_eq!(reply.status, 200);
    let value = reply.json();
    let names: Vec<&str> = value["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["name"].as_str().unwrap())
        .collect();
    use fair::fairing::catalog::{Catalog, MethodKind};
    let catalog = Catalog::builtin();
    let registered: Vec<&str> = [MethodKind::Curve, MethodKind::Surface]
        .into_iter()
        .flat_map(|kind| catalog.methods(kind))
        .map(|m| m.name())
        .collect();
    assert_eq!(names, registered);
    let two_phase = value["methods"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "two-phase")
        .unwrap();
    assert_eq!(two_phase["planar_only"], true, "two-phase refuses spatial curves");
    let strain = value["methods"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "strain-energy")
        .unwrap();
    assert_eq!(strain["planar_only"], false);
    let smoothing = value["methods"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["name"] == "smoothing-spline")
        .unwrap();
    let p = &smoothing["schema"]["properties"]["p"];
    assert!(p["description"].as_str().is_some_and(|d| !d.is_empty()), "{p}");
    assert!(!p["default"].is_null(), "{p}");
    assert_eq!(value["defaults"]["function"], "jump-lsq");
}

#[test]
fn datasets_are_listed_and_read_as_the_command_reads_them() {
    let dir_guard = scratch("datasets");
    let dir = dir_guard.path();
    std::fs::create_dir_all(dir.join("lines")).unwrap();
    std::fs::copy(root().join(WL03), dir.join("lines/wl_03.csv")).unwrap();
    std::fs::write(dir.join("lines/readme.md"), "not data").unwrap();
    let server = Served::start(&[&dir.join("lines").display().to_string()]);
    let list = get(&server.address, "/api/datasets").json();
    let names: Vec<&str> = list["datasets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["name"].as_str().unwrap())
        .collect();
    assert!(
        names.contains(&"gunnerus-wl03") && names.contains(&"teapot-body"),
        "{names:?}"
    );
    assert!(names.contains(&"lines/wl_03.csv"), "{names:?}");
    assert!(!names.iter().any(|n| n.ends_with("readme.md")), "{names:?}");

    let expected = command_report(&["inspect", &file(WL03)], &dir.join("inspect.json"));
    for name in ["gunnerus-wl03", "lines/wl_03.csv", "lines%2Fwl_03.csv"] {
        let reply = get(&server.address, &format!("/api/datasets/{name}"));
        assert_eq!(
            reply.status,
            200,
            "{name}: {}",
            String::from_utf8_lossy(&reply.body)
        );
        let loaded = reply.json();
        assert_eq!(loaded["type"], "curve");
        assert_eq!(bits(&loaded["points"]), file_bits(&root().join(WL03)), "{name}");
        assert_eq!(loaded["report"], expected, "{name}");
        let drawing = &loaded["drawing"];
        assert_eq!(drawing["z"].as_array().unwrap().len(), 62);
        assert!(drawing["comb"]["points"].as_array().unwrap().len() > 62);
    }
    let surface = get(&server.address, "/api/datasets/teapot-body").json();
    assert_eq!(
        (
            surface["type"].as_str(),
            surface["rows"].as_u64(),
            surface["columns"].as_u64()
        ),
        (Some("surface"), Some(13), Some(13))
    );
    let expected = command_report(&["inspect", &file(TEAPOT)], &dir.join("teapot.json"));
    assert_eq!(surface["report"], expected);
    assert!(!surface["drawing"]["highlights"]["lines"]
        .as_array()
        .unwrap()
        .is_empty());
}

#[test]
fn inspect_takes_a_file_text_points_or_a_grid() {
    let server = Served::start(&[]);
    let dir_guard = scratch("inspect");
    let dir = dir_guard.path();
    let text = std::fs::read_to_string(root().join(WL03)).unwrap();
    let expected = command_report(&["inspect", &file(WL03)], &dir.join("r.json"));
    let by_text = post(
        &server.address,
        "/api/inspect",
        &json!({ "name": "wl.csv", "text": text }).to_string(),
    );
    assert_eq!(by_text.status, 200);
    let by_text = by_text.json();
    assert_eq!(by_text["report"], expected);
    assert_eq!(by_text["name"], "wl.csv");
    let by_points = post(
        &server.address,
        "/api/inspect",
        &json!({ "points": by_text["points"] }).to_string(),
    )
    .json();
    assert_eq!(by_points["report"], expected);
    let parametric = command_report(
        &["inspect", &file(WL03), "--kind", "parametric"],
        &dir.join("p.json"),
    );
    let as_parametric = post(
        &server.address,
        "/api/inspect",
        &json!({ "points": by_text["points"], "kind": "parametric" }).to_string(),
    )
    .json();
    assert_eq!(as_parametric["report"], parametric);

    let teapot = get(&server.address, "/api/datasets/teapot-body").json();
    let grid = post(
        &server.address,
        "/api/inspect",
        &json!({ "rows": 13, "columns": 13, "points": teapot["points"] }).to_string(),
    );
    assert_eq!(grid.status, 200);
    assert_eq!(grid.json()["report"], teapot["report"]);
}

/// A fairing request and the command line it stands for.
struct Case {
    dataset: &'static str,
    file: &'static str,
    body: Value,
    args: Vec<&'static str>,
}

fn curve_cases() -> Vec<Case> {
    vec![
        Case {
            dataset: "gunnerus-wl03",
            file: WL03,
            body: json!({ "method": "strain-energy", "constraints": { "points": [12] } }),
            args: vec!["--method", "strain-energy", "--points", "12"],
        },
        Case {
            dataset: "gunnerus-wl03",
            file: WL03,
            body: json!({}),
            args: vec![],
        },
        Case {
            dataset: "gunnerus-wl03",
            file: WL03,
            body: json!({ "constraints": { "corners": "none" } }),
            args: vec!["--corners", "none"],
        },
        Case {
            dataset: "gunnerus-wl03",
            file: WL03,
            body: json!({ "constraints": { "corners": "auto" } }),
            args: vec!["--corners", "auto"],
        },
        Case {
            dataset: "gunnerus-wl03",
            file: WL03,
            body: json!({ "constraints": { "corners": [20, 40] } }),
            args: vec!["--corners", "20,40"],
        },
        Case {
            dataset: "ua2-180-upper",
            file: "data/airfoil_ua2-180/ua2-180_upper.csv",
            body: json!({
                "method": "smoothing-spline",
                "params": { "p": 0.9999, "rule": null },
                "constraints": { "fixed": [5, 9], "tolerance": 0.002, "clamp-ends": "g0" }
            }),
            args: vec![
                "--method",
                "smoothing-spline",
                "--set",
                "p=0.9999",
                "--fixed",
                "5,9",
                "--tolerance",
                "0.002",
                "--clamp-ends",
                "g0",
            ],
        },
        Case {
            dataset: "block-island-sheer",
            file: "data/hull_block_island_boat/sheer_3d.csv",
            body: json!({ "method": "kjellander", "kind": "parametric", "params": { "max-iterations": 50 } }),
            args: vec![
                "--method",
                "kjellander",
                "--kind",
                "parametric",
                "--set",
                "max-iterations=50",
            ],
        },
    ]
}

#[test]
fn curve_fairing_answers_the_command_report_and_points() {
    let server = Served::start(&[]);
    let dir_guard = scratch("curve");
    let dir = dir_guard.path();
    for (k, case) in curve_cases().into_iter().enumerate() {
        let loaded = get(&server.address, &format!("/api/datasets/{}", case.dataset)).json();
        let mut body = case.body.clone();
        body["points"] = loaded["points"].clone();
        let reply = post(&server.address, "/api/curve", &body.to_string());
        assert_eq!(
            reply.status,
            200,
            "{}: {}",
            case.dataset,
            String::from_utf8_lossy(&reply.body)
        );
        let answer = reply.json();
        let out = dir.join(format!("out{k}.csv"));
        let path = file(case.file);
        let mut args = vec!["curve", path.as_str(), "-o", out.to_str().unwrap()];
        args.extend(case.args.iter().copied());
        let expected = command_report(&args, &dir.join(format!("r{k}.json")));
        assert_eq!(untimed(&answer["report"]), untimed(&expected), "{}", case.dataset);
        assert_eq!(bits(&answer["points"]), file_bits(&out), "{}", case.dataset);
        let (before, after) = (&answer["drawing"]["before"], &answer["drawing"]["after"]);
        assert_eq!(
            before["view"].as_array().unwrap().len(),
            after["view"].as_array().unwrap().len()
        );
        assert_eq!(
            before, &loaded["drawing"],
            "{}: the drawing before is the loaded one",
            case.dataset
        );
    }
}

#[test]
fn surface_fairing_answers_the_command_report_and_grid() {
    let server = Served::start(&[]);
    let dir_guard = scratch("surface");
    let dir = dir_guard.path();
    let teapot = get(&server.address, "/api/datasets/teapot-body").json();
    for (k, (body, args)) in [
        // The default method (jump-lsq) with a fixed node, then the paper's with bad points.
        (json!({ "constraints": { "fixed": [84] } }), vec!["--fixed", "84"]),
        (
            json!({ "method": "zhang-cheng", "constraints": { "points": [20, 21, 33, 34] } }),
            vec!["--method", "zhang-cheng", "--points", "20,21,33,34"],
        ),
        (
            json!({ "method": "kjellander", "params": { "max-steps": 40 }, "constraints": { "clamp-ends": "g0" } }),
            vec!["--method", "kjellander", "--set", "max-steps=40", "--clamp-ends", "g0"],
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let mut body = body;
        body["rows"] = json!(13);
        body["columns"] = json!(13);
        body["points"] = teapot["points"].clone();
        let reply = post(&server.address, "/api/surface", &body.to_string());
        assert_eq!(reply.status, 200, "{}", String::from_utf8_lossy(&reply.body));
        let answer = reply.json();
        let out = dir.join(format!("out{k}.csv"));
        let path = file(TEAPOT);
        let mut command = vec!["surface", path.as_str(), "-o", out.to_str().unwrap()];
        command.extend(args.iter().copied());
        let expected = command_report(&command, &dir.join(format!("r{k}.json")));
        assert_eq!(untimed(&answer["report"]), untimed(&expected));
        // The command writes the grid i,j,x,y,z row by row, as the API's points are ordered.
        let written: Vec<Vec<u64>> = std::fs::read_to_string(&out)
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').skip(2).map(|c| c.parse::<f64>().unwrap().to_bits()).collect())
            .collect();
        assert_eq!(bits(&answer["points"]), written);
        assert_eq!(answer["drawing"]["before"], teapot["drawing"]);
        assert!(!answer["drawing"]["after"]["highlights"]["lines"].as_array().unwrap().is_empty());
    }
}

#[test]
fn bad_requests_are_4xx_with_a_message_and_the_server_lives_on() {
    let mut server = Served::start(&["--max-upload", "20000"]);
    let a = server.address.clone();
    let points = get(&a, "/api/datasets/gunnerus-wl03").json()["points"].clone();
    let with = |extra: Value| {
        let mut body = json!({ "points": points });
        for (k, v) in extra.as_object().unwrap() {
            body[k] = v.clone();
        }
        body.to_string()
    };
    let posts: Vec<(&str, String, u16, &str)> = vec![
        (
            "/api/curve",
            r#"{"points": [[0, 0], [1, "#.into(),
            400,
            "request body",
        ),
        (
            "/api/curve",
            r#"{"points": [[0, 0], [1, NaN], [2, 0]]}"#.into(),
            400,
            "NaN",
        ),
        (
            "/api/curve",
            r#"{"points": [[0, 0], [1, 1e999], [2, 0]]}"#.into(),
            400,
            "request body",
        ),
        (
            "/api/curve",
            r#"{"points": [[0, 0], [1, 1], [2, 0]], "colour": "red"}"#.into(),
            400,
            "unknown field `colour`",
        ),
        (
            "/api/curve",
            with(json!({ "method": "frobnicate" })),
            400,
            "unknown curve method `frobnicate`",
        ),
        (
            "/api/curve",
            with(json!({ "params": { "wiggle": 1 } })),
            400,
            "params: `wiggle` is not a parameter of `jump-lsq`",
        ),
        (
            "/api/curve",
            with(json!({ "method": "smoothing-spline", "params": { "p": "lots" } })),
            400,
            "`p`",
        ),
        (
            "/api/curve",
            with(json!({ "params": { "max-passes": [1] } })),
            400,
            "must be a number, a string or a boolean",
        ),
        (
            "/api/curve",
            with(json!({ "constraints": { "fixed": [62] } })),
            400,
            "constraints.fixed: index 62 is past the last point",
        ),
        (
            "/api/curve",
            with(json!({ "constraints": { "points": [3] } })),
            400,
            "constraints.points",
        ),
        (
            "/api/curve",
            with(json!({ "constraints": { "tolerance": -1 } })),
            400,
            "constraints.tolerance",
        ),
        (
            "/api/curve",
            with(json!({ "constraints": { "clamp-ends": "g7" } })),
            400,
            "g0, g1, g2",
        ),
        (
            "/api/curve",
            with(json!({ "constraints": { "corners": "often" } })),
            400,
            "constraints.corners",
        ),
        (
            "/api/curve",
            with(json!({ "kind": "spiral" })),
            400,
            "kind: `spiral`",
        ),
        (
            "/api/curve",
            r#"{"points": [[0, 0], [1, 1]]}"#.into(),
            400,
            "at least 3",
        ),
        (
            "/api/curve",
            r#"{"points": [[0, 0], [1, 1, 1], [2, 0]]}"#.into(),
            400,
            "point 1 has 3 coordinates",
        ),
        (
            "/api/curve",
            r#"{"points": [[0], [1], [2]]}"#.into(),
            400,
            "point 0 has 1 coordinates",
        ),
        (
            "/api/curve",
            r#"{"points": [[0, 0], [0, 0], [0, 0]], "kind": "parametric"}"#.into(),
            400,
            "points",
        ),
        ("/api/curve", r#"[1, 2]"#.into(), 400, "request body"),
        (
            "/api/surface",
            r#"{"rows": 3, "columns": 3, "points": [[0, 0, 0]]}"#.into(),
            400,
            "rows × columns",
        ),
        (
            "/api/surface",
            r#"{"rows": 2, "columns": 2, "points": [[0,0,0],[0,1,0],[1,0,0],[1,1,0]]}"#.into(),
            400,
            "at least 3 × 3",
        ),
        (
            "/api/surface",
            r#"{"rows": 18446744073709551615, "columns": 2, "points": []}"#.into(),
            400,
            "rows × columns",
        ),
        (
            "/api/inspect",
            r#"{"text": "x,y\n0,0\n1,oops\n"}"#.into(),
            400,
            "upload:3",
        ),
        ("/api/inspect", r#"{}"#.into(), 400, "give `text`"),
    ];
    for (path, body, status, needle) in &posts {
        let reply = post(&a, path, body);
        assert_eq!(
            reply.status,
            *status,
            "{path} {body}: {}",
            String::from_utf8_lossy(&reply.body)
        );
        let message = reply.error();
        assert!(
            message.contains(needle),
            "{path} {body}: `{needle}` not in {message:?}"
        );
    }
    let gets: Vec<(&str, &str, u16, &str)> = vec![
        ("GET", "/api/nothing", 404, "no route"),
        ("GET", "/api/curve", 405, "use POST"),
        ("PUT", "/api/methods", 405, "use GET"),
        (
            "GET",
            "/api/datasets/no-such-set",
            404,
            "no data set `no-such-set`",
        ),
        (
            "GET",
            "/api/datasets/../Cargo.toml",
            400,
            "outside the data folders",
        ),
        (
            "GET",
            "/api/datasets/%2e%2e%2fCargo.toml",
            400,
            "outside the data folders",
        ),
        (
            "GET",
            "/api/datasets/x%2F..%2F..%2Fetc%2Fpasswd",
            400,
            "outside the data folders",
        ),
        (
            "GET",
            "/api/datasets//etc/passwd",
            400,
            "outside the data folders",
        ),
        ("GET", "/api/datasets/%ff", 400, "percent-encoded"),
    ];
    for (method, path, status, needle) in &gets {
        let reply = request(&a, method, path, &[], b"").unwrap();
        assert_eq!(reply.status, *status, "{method} {path}");
        assert!(
            reply.error().contains(needle),
            "{method} {path}: {}",
            reply.error()
        );
    }
    // Not declared JSON: refused before it is read.
    let reply = request(&a, "POST", "/api/curve", &[("Content-Type", "text/plain")], b"{}").unwrap();
    assert_eq!(reply.status, 415);
    // A huge upload, sent in full, and one only declared huge: 413 without reading it.
    let big = format!(r#"{{"text": "{}"}}"#, "0,0\\n".repeat(10_000));
    let reply = post(&a, "/api/inspect", &big);
    assert_eq!(reply.status, 413);
    assert!(
        reply.error().contains("more than the limit of 20000"),
        "{}",
        reply.error()
    );
    let declared = format!("POST /api/curve HTTP/1.1\r\nHost: {a}\r\nContent-Type: application/json\r\nContent-Length: 99999999999999999\r\n\r\n{{");
    assert_eq!(raw(&a, declared.as_bytes()).unwrap().status, 413);
    let chunked = format!("POST /api/curve HTTP/1.1\r\nHost: {a}\r\nContent-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n2\r\n{{}}\r\n0\r\n\r\n");
    assert_eq!(raw(&a, chunked.as_bytes()).unwrap().status, 411);
    assert_eq!(raw(&a, b"BLAH\r\n\r\n").unwrap().status, 400);
    let long = format!("GET /{} HTTP/1.1\r\nHost: {a}\r\n\r\n", "a".repeat(70_000));
    assert_eq!(raw(&a, long.as_bytes()).unwrap().status, 431);
    // Another site's name for this server (DNS rebinding) is refused.
    let foreign = b"GET /api/datasets HTTP/1.1\r\nHost: evil.example:80\r\n\r\n";
    let reply = raw(&a, foreign).unwrap();
    assert_eq!(reply.status, 403);
    assert!(reply.error().contains("localhost only"));
    // A client that connects and leaves, or sends half a head and leaves.
    drop(std::net::TcpStream::connect(&a).unwrap());
    {
        use std::io::Write;
        let mut half = std::net::TcpStream::connect(&a).unwrap();
        half.write_all(b"POST /api/curve HTTP/1.1\r\nContent-Le").unwrap();
    }
    assert!(server.alive(), "the server died");
    let reply = get(&a, "/api/methods");
    assert_eq!(reply.status, 200);
    assert!(server.alive());
}

#[test]
fn fifty_concurrent_requests_are_answered_as_sequential_ones() {
    let server = Served::start(&[]);
    let a = server.address.clone();
    let names = [
        "gunnerus-wl03",
        "ua2-180-upper",
        "r140-upper",
        "block-island-wl36",
        "naca2412-upper",
    ];
    let loaded: Vec<Value> = names
        .iter()
        .map(|n| get(&a, &format!("/api/datasets/{n}")).json())
        .collect();
    let teapot = get(&a, "/api/datasets/teapot-body").json();
    // 50 different requests: every user's own data, method and bad points.
    let requests: Vec<(&str, String)> = (0..50)
        .map(|k| {
            let points = &loaded[k % names.len()]["points"];
            let n = points.as_array().unwrap().len();
            // Surfaces are a tenth: their highlight lines are slow in a debug build.
            match k % 10 {
                0 | 5 => ("/api/curve", json!({ "points": points, "method": "strain-energy", "constraints": { "points": [3 + k % (n - 6)] } })),
                1 | 6 => ("/api/curve", json!({ "points": points, "method": "smoothing-spline", "params": { "p": 0.99 + 0.0001 * k as f64 } })),
                2 | 7 => ("/api/curve", json!({ "points": points, "method": "kjellander", "params": { "max-iterations": 5 + k } })),
                3 | 8 => ("/api/inspect", json!({ "points": points, "kind": if k % 2 == 0 { "parametric" } else { "auto" } })),
                4 => ("/api/curve", json!({ "points": points, "constraints": { "fixed": [1, 2], "clamp-ends": "g0" } })),
                _ => {
                    let node = (1 + k % 11) * 13 + 1 + (k / 5) % 11;
                    ("/api/surface", json!({ "rows": 13, "columns": 13, "points": teapot["points"], "method": "zhang-cheng", "constraints": { "points": [node] } }))
                }
            }
        })
        .map(|(path, body)| (path, body.to_string()))
        .collect();
    let answer = |(path, body): &(&str, String)| {
        let reply = post(&a, path, body);
        (reply.status, untimed(&reply.json()))
    };
    let sequential: Vec<(u16, Value)> = requests.iter().map(answer).collect();
    assert!(
        sequential.iter().all(|(status, _)| *status == 200),
        "a request failed"
    );
    let concurrent: Vec<(u16, Value)> = std::thread::scope(|scope| {
        let handles: Vec<_> = requests.iter().map(|r| scope.spawn(move || answer(r))).collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("client thread"))
            .collect()
    });
    for (k, (s, c)) in sequential.iter().zip(&concurrent).enumerate() {
        assert!(s == c, "request {k} answered differently when concurrent");
    }
}

#[test]
fn a_missing_file_or_a_busy_port_exits_2_with_one_line() {
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_fair"))
            .arg("serve")
            .args(args)
            .output()
            .expect("run fair serve")
    };
    let missing = run(&["--port", "0", "no/such/file.csv"]);
    assert_eq!(missing.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&missing.stderr);
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("fair: no/such/file.csv: cannot read"),
        "{stderr}"
    );
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let busy = run(&["--port", &port]);
    assert_eq!(busy.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&busy.stderr);
    assert!(
        stderr.starts_with(&format!("fair: --port: cannot listen on 127.0.0.1:{port}")),
        "{stderr}"
    );
}

#[test]
fn points_keep_their_bits_through_the_api() {
    // Doubles with 17 significant digits, as faired points have: a best-effort JSON float
    // parser changes about one in thirteen of these by an ULP.
    let server = Served::start(&[]);
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let points: Vec<[f64; 2]> = (0..300).map(|i| [i as f64 + next(), 10.0 * next()]).collect();
    let expected: Vec<Vec<u64>> = points
        .iter()
        .map(|p| p.iter().map(|c| c.to_bits()).collect())
        .collect();
    let body = json!({ "points": points, "kind": "parametric" }).to_string();
    let inspected = post(&server.address, "/api/inspect", &body);
    assert_eq!(inspected.status, 200);
    assert_eq!(bits(&inspected.json()["points"]), expected);
    // A fairing that moves one point gives every other point back unchanged.
    let body = json!({ "points": points, "kind": "parametric", "method": "strain-energy", "constraints": { "points": [150] } })
        .to_string();
    let faired = post(&server.address, "/api/curve", &body).json();
    assert_eq!(faired["report"]["moved"], json!([150]));
    let back = bits(&faired["points"]);
    for (i, (b, e)) in back.iter().zip(&expected).enumerate() {
        assert!(i == 150 || b == e, "point {i} changed");
    }
}

#[test]
fn cad_download_is_the_command_s_cad_file() {
    let server = Served::start(&[]);
    let dir_guard = scratch("cad");
    let dir = dir_guard.path();
    let loaded = get(&server.address, "/api/datasets/gunnerus-wl03").json();
    let body = json!({
        "name": "wl_03.csv",
        "points": loaded["points"],
        "method": "strain-energy",
        "constraints": { "points": [12] },
        "format": "iges",
    });
    let reply = post(&server.address, "/api/cad", &body.to_string());
    assert_eq!(reply.status, 200, "{}", String::from_utf8_lossy(&reply.body));
    assert_eq!(reply.header("Content-Type"), Some("model/iges"));
    assert_eq!(
        reply.header("Content-Disposition"),
        Some("attachment; filename=\"wl_03-strain-energy.igs\"")
    );
    let summary: Value = serde_json::from_str(reply.header("X-Fair-Cad").expect("the cad object")).unwrap();
    // The waterline is a function: strain-energy's y is kept at the input's x, so the curve
    // written is the spline function through the result, not the method's Hermite spline.
    assert_eq!(summary["representation"], "spline-function");
    let served = cad::read(&String::from_utf8(reply.body.clone()).unwrap(), cad::Format::Iges).unwrap();
    // The command's file for the same run holds the same curve, bit for bit.
    let out = dir.join("wl03.igs");
    let report = command_report(
        &[
            "curve",
            &file(WL03),
            "--method",
            "strain-energy",
            "--points",
            "12",
            "-q",
            "-o",
            out.to_str().unwrap(),
        ],
        &dir.join("wl03.json"),
    );
    let written = cad::read_path(&out, None).unwrap();
    assert_eq!(served.curves.len(), 1);
    assert_eq!(served.curves[0].curve, written.curves[0].curve);
    assert_eq!(summary["control_points"], report["cad"]["control_points"]);

    // Points taken as they are ("fair": false), with a rebuild: the file has its control points.
    let body = json!({ "points": loaded["points"], "format": "step", "fair": false, "control-points": 10 });
    let reply = post(&server.address, "/api/cad", &body.to_string());
    assert_eq!(reply.status, 200, "{}", String::from_utf8_lossy(&reply.body));
    let model = cad::read(&String::from_utf8(reply.body).unwrap(), cad::Format::Step).unwrap();
    assert_eq!(model.curves[0].curve.control_points().len(), 10);

    // A surface in STEP; refusals name the request's field.
    let teapot = get(&server.address, "/api/datasets/teapot-body").json();
    let surface = json!({ "rows": teapot["rows"], "columns": teapot["columns"], "points": teapot["points"], "format": "step" });
    let reply = post(&server.address, "/api/cad", &surface.to_string());
    assert_eq!(reply.status, 200, "{}", String::from_utf8_lossy(&reply.body));
    let model = cad::read(&String::from_utf8(reply.body).unwrap(), cad::Format::Step).unwrap();
    assert_eq!(model.surfaces.len(), 1);
    let mut dxf = surface.clone();
    dxf["format"] = json!("dxf");
    let mut rebuilt = surface.clone();
    rebuilt["control-points"] = json!(6);
    let mut unknown = body.clone();
    unknown["format"] = json!("obj");
    let mut few = body.clone();
    few["control-points"] = json!(3);
    for (request, field) in [
        (dxf, "format:"),
        (rebuilt, "control-points:"),
        (unknown, "format:"),
        (few, "control-points:"),
    ] {
        let reply = post(&server.address, "/api/cad", &request.to_string());
        assert_eq!(reply.status, 400, "{field}");
        assert!(reply.error().starts_with(field), "{}", reply.error());
    }
}
