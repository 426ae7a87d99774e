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
