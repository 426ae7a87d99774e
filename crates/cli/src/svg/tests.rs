//! Every SVG the toolkit writes is well-formed XML and holds what was drawn.

use super::*;

fn parse(svg: &str) -> roxmltree::Document<'_> {
    roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("not XML: {e}\n{svg}"))
}

fn count(doc: &roxmltree::Document, tag: &str) -> usize {
    doc.descendants().filter(|n| n.has_tag_name(tag)).count()
}

fn circle_centres(doc: &roxmltree::Document) -> Vec<(f64, f64)> {
    doc.descendants()
        .filter(|n| n.has_tag_name("circle") && n.parent().is_some_and(|p| p.has_tag_name("g")))
        .filter(|n| n.attribute("r") != Some("3"))
        .map(|n| {
            let get = |a: &str| {
                n.attribute(a)
                    .and_then(|v| v.parse::<f64>().ok())
                    .unwrap_or(f64::NAN)
            };
            (get("cx"), get("cy"))
        })
        .collect()
}

fn all_series_figure() -> Figure {
    let curve: Vec<[f64; 2]> = (0..50)
        .map(|i| i as f64 / 49.0)
        .map(|t| [t, (6.0 * t).sin()])
        .collect();
    let normals: Vec<[f64; 2]> = vec![[0.0, 1.0]; curve.len()];
    let lengths: Vec<f64> = curve.iter().map(|p| p[1]).collect();
    let grid: Vec<Vec<f64>> = (0..5).map(|i| (0..4).map(|j| (i * j) as f64).collect()).collect();
    Figure::new()
        .with_title("Fairing <test> & \"quotes\"")
        .with_columns(2)
        .with_panel(
            Panel::new("curve")
                .with_x_label("x")
                .with_y_label("y")
                .with_equal_aspect(true)
                .with(Line::new(curve.clone()).with_label("input"))
                .with(Markers::new(curve.clone()).with_label("points"))
                .with(
                    Comb::new(curve.clone(), normals, lengths)
                        .with_auto_scale(0.1)
                        .with_label("comb"),
                ),
        )
        .with_panel(
            Panel::new("z_i")
                .with_x_label("i")
                .with(Bars::indexed(vec![0.1, -0.4, 0.3, 2.0]).with_label("z")),
        )
        .with_panel(Panel::new("z_ij").with(ColorMap::indexed(grid).with_label("z_ij")))
}

#[test]
fn every_figure_is_xml_with_its_elements() {
    let svg = all_series_figure().to_svg();
    let doc = parse(&svg);
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    // input line + comb envelope
    assert!(count(&doc, "polyline") >= 2, "{svg}");
    // comb teeth
    assert!(count(&doc, "path") >= 1);
    // 50 markers (+ legend swatch)
    assert!(count(&doc, "circle") >= 50);
    // 4 bars + 20 colour cells + frames
    assert!(count(&doc, "rect") >= 24);
    assert_eq!(count(&doc, "clipPath"), 3);
    assert!(!svg.contains("NaN") && !svg.contains("inf"));
}

#[test]
fn text_is_escaped_and_read_back() {
    let svg = all_series_figure().to_svg();
    let doc = parse(&svg);
    let title = doc
        .descendants()
        .find(|n| n.has_tag_name("text"))
        .and_then(|n| n.text());
    assert_eq!(title, Some("Fairing <test> & \"quotes\""));
    assert_eq!(escape("a<b>&'\"\u{1}"), "a&lt;b&gt;&amp;&apos;&quot;");
}

#[test]
fn comb_draws_one_tooth_per_point_and_an_envelope_through_the_tips() {
    let base = vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
    let comb = Comb::new(base, vec![[0.0, 1.0]; 3], vec![1.0, -1.0, 0.5]);
    assert_eq!(comb.tips(), vec![[0.0, 1.0], [1.0, -1.0], [2.0, 0.5]]);
    let svg = Figure::new().with_panel(Panel::new("comb").with(comb)).to_svg();
    let doc = parse(&svg);
    let path = doc
        .descendants()
        .find(|n| n.has_tag_name("path"))
        .and_then(|n| n.attribute("d"))
        .unwrap();
    assert_eq!(path.matches('M').count(), 3);
    let envelope = doc.descendants().find(|n| n.has_tag_name("polyline")).unwrap();
    assert_eq!(envelope.attribute("points").unwrap().split(' ').count(), 3);
}

#[test]
fn equal_aspect_keeps_circles_round() {
    let circle = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [0.0, 0.0]];
    for size in [(800.0, 300.0), (300.0, 800.0)] {
        let svg = Figure::new()
            .with_panel_size(size.0, size.1)
            .with_panel(
                Panel::new("round")
                    .with_equal_aspect(true)
                    .with(Markers::new(circle)),
            )
            .to_svg();
        let c = circle_centres(&parse(&svg));
        assert_eq!(c.len(), 5);
        let horizontal = c[0].0 - c[4].0;
        let vertical = c[4].1 - c[1].1;
        assert!(
            horizontal > 1.0 && (horizontal - vertical).abs() < 0.02,
            "{horizontal} {vertical}"
        );
    }
    // Without it the panel is stretched.
    let svg = Figure::new()
        .with_panel_size(800.0, 300.0)
        .with_panel(Panel::new("s").with(Markers::new(circle)))
        .to_svg();
    let c = circle_centres(&parse(&svg));
    assert!((c[0].0 - c[4].0) > 2.0 * (c[4].1 - c[1].1));
}

#[test]
fn non_finite_points_break_lines_and_are_never_written() {
    let line = Line::new([
        [0.0, 0.0],
        [1.0, 1.0],
        [f64::NAN, 2.0],
        [3.0, 3.0],
        [4.0, f64::INFINITY],
        [5.0, 1.0],
        [6.0, 0.0],
    ]);
    let svg = Figure::new().with_panel(Panel::new("gaps").with(line)).to_svg();
    let doc = parse(&svg);
    // runs: [0,1], [3] (dropped, single), [5,6]
    assert_eq!(count(&doc, "polyline"), 2);
    assert!(!svg.to_lowercase().contains("nan") && !svg.contains("inf"));
}

#[test]
fn empty_and_degenerate_panels_still_render() {
    let svg = Figure::new()
        .with_panel(Panel::new("empty"))
        .with_panel(Panel::new("point").with(Markers::new([[2.0, 2.0]])))
        .to_svg();
    let doc = parse(&svg);
    assert_eq!(count(&doc, "circle"), 1);
    let svg = Figure::new().to_svg();
    parse(&svg);
}

#[test]
fn write_saves_the_document() {
    let scratch = tempfile::Builder::new()
        .prefix("fair-cli-svg-")
        .tempdir()
        .unwrap();
    let path = scratch.path().join("plot.svg");
    all_series_figure().write(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    parse(&text);
    let e = all_series_figure()
        .write(std::path::Path::new("/nonexistent/dir/p.svg"))
        .unwrap_err();
    assert_eq!(e.exit_code(), 2);
}

/// The points of every polyline, in pixels.
fn polylines(doc: &roxmltree::Document) -> Vec<Vec<(f64, f64)>> {
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .map(|n| {
            n.attribute("points")
                .unwrap_or_default()
                .split(' ')
                .filter_map(|xy| {
                    let (x, y) = xy.split_once(',')?;
                    Some((x.parse().ok()?, y.parse().ok()?))
                })
                .collect()
        })
        .collect()
}

fn bounding_box(points: &[(f64, f64)]) -> [f64; 4] {
    points.iter().fold(
        [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY],
        |b, &(x, y)| [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)],
    )
}

/// A 10^6-point curve with its markers and comb is thinned per pixel column to a plot of a
/// few hundred kB (the whole would be some 100 MB), and what is kept holds every extreme:
/// the thinned polyline's bounding box is the whole one's, to the printed 0.01 px.
#[test]
fn a_million_point_plot_is_thinned_and_keeps_its_extremes() {
    let n = 1_000_000;
    // A noisy sine with one spike, so that the extremes are single points.
    let curve: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64;
            let noise = ((i * 7919) % 1000) as f64 / 1e5;
            let spike = if i == 123_457 { 3.0 } else { 0.0 };
            [t, (20.0 * t).sin() + noise + spike]
        })
        .collect();
    let normals = vec![[0.0, 1.0]; n];
    // Curvature as noisy as a million noisy points give: the comb's tips jump about.
    let lengths: Vec<f64> = (0..n)
        .map(|i| curve[i][1].cos() + ((i * 104_729) % 997) as f64 / 300.0)
        .collect();
    let heights: Vec<f64> = curve.iter().map(|p| p[1] - 0.5).collect();
    let figure = Figure::new()
        .with_panel(
            Panel::new("curve")
                .with(Line::new(curve.clone()))
                .with(Markers::new(curve.clone()))
                .with(Comb::new(curve.clone(), normals, lengths)),
        )
        .with_panel(Panel::new("z_i").with(Bars::new((0..n).map(|i| i as f64).collect(), heights)));
    let svg = figure.to_svg();
    assert!(svg.len() < 8_000_000, "{} bytes", svg.len());
    let doc = parse(&svg);
    let lines = polylines(&doc);
    // The curve's line: at most 4 points per pixel column; the markers at the same places.
    let line = &lines[0];
    assert!(line.len() < 6 * 1000, "{} points", line.len());
    let markers = circle_centres(&doc);
    assert!(markers.len() < 6 * 1000, "{} markers", markers.len());
    // The comb's envelope, and the bars: two per pixel column at most.
    assert!(
        lines.iter().all(|l| l.len() < 12 * 1000),
        "{:?}",
        lines.iter().map(Vec::len).collect::<Vec<_>>()
    );
    assert!(
        count(&doc, "rect") < 2 * 1000 + 20,
        "{} rects",
        count(&doc, "rect")
    );
    assert_eq!(bounding_box(&markers), bounding_box(line));
    // The line alone, against a line through only its first, last, lowest and highest
    // points: the same extent, so the same frame, and the same bounding box in pixels.
    let alone = |points: Vec<[f64; 2]>| {
        let svg = Figure::new()
            .with_panel(Panel::new("curve").with(Line::new(points)))
            .to_svg();
        let doc = parse(&svg);
        bounding_box(&polylines(&doc)[0])
    };
    let by_y = |a: &&[f64; 2], b: &&[f64; 2]| a[1].total_cmp(&b[1]);
    let extremes = vec![
        curve[0],
        *curve.iter().min_by(by_y).unwrap(),
        *curve.iter().max_by(by_y).unwrap(),
        curve[n - 1],
    ];
    assert_eq!(alone(curve), alone(extremes));
}

/// Thinning keeps, in order, the first, last and extreme points of each run of points within
/// a two-pixel box, and leaves a short series whole.
#[test]
fn thinning_keeps_each_boxes_extremes_in_order() {
    use super::figure::thin;
    let run = [
        (0.2, 5.0),
        (0.5, 9.0),
        (0.7, 1.0),
        (0.9, 4.0),
        (1.1, 3.0),
        (1.5, 3.5),
    ];
    assert_eq!(thin(&run, 100.0), (0..run.len()).collect::<Vec<_>>());
    // Width 1: more than 4 points per pixel, so thinned; but each point is more than two
    // pixels above or below the one before, so each is a group of its own.
    assert_eq!(thin(&run, 1.0), (0..run.len()).collect::<Vec<_>>());
    // Jitter across a column's edge stays one group: first, greatest x, last (= highest).
    let jitter: Vec<(f64, f64)> = (0..40)
        .map(|k| (10.0 + 0.3 * (k % 2) as f64 - 0.1, 10.0 + 0.01 * k as f64))
        .collect();
    assert_eq!(thin(&jitter, 1.0), vec![0, 1, 39]);
    // Two boxes ([0, 2) and [2, 4) in x): each keeps its extremes, in order.
    let long: Vec<(f64, f64)> = (0..200)
        .map(|k| (k as f64 / 50.0, ((k * 37) % 11) as f64 / 10.0))
        .collect();
    let kept = thin(&long, 1.0);
    assert!(kept.windows(2).all(|w| w[0] < w[1]), "{kept:?}");
    assert_eq!((kept[0], *kept.last().unwrap()), (0, 199));
    assert!(kept.len() <= 12, "{kept:?}");
    for half in [0.0, 1.0] {
        let inside = |p: &&(f64, f64)| (p.0 / 2.0).floor() == half;
        let ys: Vec<f64> = long.iter().filter(inside).map(|p| p.1).collect();
        let kept_ys: Vec<f64> = kept
            .iter()
            .map(|&k| long[k])
            .collect::<Vec<_>>()
            .iter()
            .filter(inside)
            .map(|p| p.1)
            .collect();
        let max = |v: &[f64]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!((min(&kept_ys), max(&kept_ys)), (min(&ys), max(&ys)));
    }
}
