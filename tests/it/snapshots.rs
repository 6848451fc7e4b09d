//! Snapshots of every scene's exported CSV (quick mode), compared with stored fixtures in
//! `tests/fixtures/snapshots/<id>.csv` row by row: the same panel, series and style, and
//! numbers equal to 1e-7 relative (plus 1e-12 of the column's range, for values near zero).
//! Regenerate after an intended change with `UPDATE_SNAPSHOTS=1 cargo test --release snapshots`
//! and review the diff. The same quick figures are checked for legends that cover data.

use std::sync::OnceLock;

use adhesion::figure::Figure;
use adhesion::job::Job;
use adhesion::render::data::{csv, parse_csv};
use adhesion::scenes;

use crate::common::root;

const REL_TOL: f64 = 1e-7;

/// Every scene's figure in quick mode, computed once for the tests of this module.
fn quick_figures() -> &'static [(&'static str, Figure)] {
    static FIGS: OnceLock<Vec<(&'static str, Figure)>> = OnceLock::new();
    FIGS.get_or_init(|| {
        scenes::all()
            .iter()
            .map(|s| {
                let id = s.info().id;
                let values = s.quick(&s.defaults()).unwrap();
                let fig = s
                    .run(&values, &Job::quiet())
                    .unwrap_or_else(|e| panic!("{id}: {e}"));
                (id, fig)
            })
            .collect()
    })
}

/// No legend box, nor the box of a panel's notes, holds a series point or a marker, in any
/// panel of any scene (the placement as the PNG renderer computes it); the two boxes do not
/// overlap.
#[test]
fn legends_cover_no_data_point_in_any_scene() {
    let mut failures = Vec::new();
    for (id, fig) in quick_figures() {
        for (k, layout) in adhesion::render::plot::panel_layouts(fig).into_iter().enumerate() {
            let Some(layout) = layout else { continue };
            for (what, b) in [("legend", layout.legend), ("notes", layout.notes)] {
                let Some((x0, y0, x1, y1)) = b else {
                    continue;
                };
                let inside = layout
                    .points
                    .iter()
                    .filter(|p| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1)
                    .count();
                if inside > 0 {
                    failures.push(format!("{id} panel {}: {inside} points under the {what}", k + 1));
                }
            }
            if let (Some(a), Some(b)) = (layout.legend, layout.notes)
                && a.0 < b.2
                && b.0 < a.2
                && a.1 < b.3
                && b.1 < a.3
            {
                failures.push(format!("{id} panel {}: the notes overlap the legend", k + 1));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Issue 34, item 4: no text drawn in a panel's frame (marker labels, contour labels) lies over
/// the plotted data (curves, markers, arrows, contour lines), over the legend or over another
/// text; the tick labels of no axis run together; no panel heading runs past its panel. In
/// every panel of every scene, with the placement the PNG renderer computes.
#[test]
fn texts_cover_no_data_nor_each_other_in_any_scene() {
    let overlap =
        |a: &(f64, f64, f64, f64), b: &(f64, f64, f64, f64)| a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3;
    let mut failures = Vec::new();
    let mut texts = 0;
    for (id, fig) in quick_figures() {
        for (k, layout) in adhesion::render::plot::panel_layouts(fig).into_iter().enumerate() {
            let Some(layout) = layout else { continue };
            let panel = k + 1;
            for (i, (text, r)) in layout.texts.iter().enumerate() {
                texts += 1;
                let under = layout
                    .data
                    .iter()
                    .filter(|p| p.0 >= r.0 && p.0 <= r.2 && p.1 >= r.1 && p.1 <= r.3)
                    .count();
                if under > 0 {
                    failures.push(format!("{id} panel {panel}: {text:?} over {under} data points"));
                }
                if layout.boxes.iter().any(|b| overlap(r, b)) {
                    failures.push(format!("{id} panel {panel}: {text:?} over the legend"));
                }
                for (other, q) in &layout.texts[i + 1..] {
                    if overlap(r, q) {
                        failures.push(format!("{id} panel {panel}: {text:?} over {other:?}"));
                    }
                }
                let (x0, x1, y0, y1) = layout.frame;
                if r.0 < x0 || r.2 > x1 || r.1 < y0 || r.3 > y1 {
                    failures.push(format!("{id} panel {panel}: {text:?} outside the frame"));
                }
            }
            for (axis, boxes) in ["x", "y"].iter().zip(&layout.ticks) {
                if boxes.windows(2).any(|w| overlap(&w[0], &w[1])) {
                    failures.push(format!("{id} panel {panel}: {axis} tick labels run together"));
                }
            }
            if layout.heading_right > layout.width {
                failures.push(format!(
                    "{id} panel {panel}: heading runs {:.0} px past the panel",
                    layout.heading_right - layout.width
                ));
            }
        }
    }
    assert!(texts > 20, "only {texts} texts placed");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn exported_csv_matches_the_stored_fixtures() {
    let update = std::env::var_os("UPDATE_SNAPSHOTS").is_some();
    let dir = root().join("tests/fixtures/snapshots");
    let mut failures = Vec::new();
    for (id, fig) in quick_figures() {
        let id = *id;
        let got = csv(fig);
        let path = dir.join(format!("{id}.csv"));
        if update {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &got).unwrap();
            continue;
        }
        let Ok(stored) = std::fs::read_to_string(&path) else {
            failures.push(format!(
                "{id}: no fixture {} (run with UPDATE_SNAPSHOTS=1)",
                path.display()
            ));
            continue;
        };
        if let Err(e) = compare(&parse_csv(&stored).unwrap(), &parse_csv(&got).unwrap()) {
            failures.push(format!("{id}: {e}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

type Row = (usize, String, String, f64, f64);

fn compare(expected: &[Row], got: &[Row]) -> Result<(), String> {
    if expected.len() != got.len() {
        return Err(format!("{} rows, expected {}", got.len(), expected.len()));
    }
    let span = |f: fn(&Row) -> f64| {
        let (lo, hi) = expected
            .iter()
            .map(f)
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
        (hi - lo).abs().max(f64::MIN_POSITIVE)
    };
    let (sx, sy) = (span(|r| r.3), span(|r| r.4));
    for (k, (e, g)) in expected.iter().zip(got).enumerate() {
        if (e.0, &e.1, &e.2) != (g.0, &g.1, &g.2) {
            return Err(format!(
                "row {}: {:?} vs expected {:?}",
                k + 2,
                (g.0, &g.1, &g.2),
                (e.0, &e.1, &e.2)
            ));
        }
        for (a, b, s) in [(g.3, e.3, sx), (g.4, e.4, sy)] {
            let ok = (a.is_nan() && b.is_nan()) || (a - b).abs() <= REL_TOL * b.abs() + 1e-12 * s;
            if !ok {
                return Err(format!("row {} ({} {}): {a} vs expected {b}", k + 2, e.1, e.2));
            }
        }
    }
    Ok(())
}

/// Heat maps go into the SVG as embedded PNG images, not one rectangle per cell: figC.1 at its
/// default resolution (six maps) was 34 MB with 393 609 rectangles.
#[test]
fn fig_c1_svg_embeds_its_maps_and_stays_under_2_mb() {
    let scene = scenes::find("figC.1").expect("scene");
    let fig = scene.run(&scene.defaults(), &Job::quiet()).expect("run");
    let svg = adhesion::render::plot::svg_string(&fig).expect("svg");
    assert!(svg.len() < 2_000_000, "figC.1.svg is {} bytes", svg.len());
    assert_eq!(svg.matches("<image ").count(), 6, "one image per map");
    assert!(
        svg.matches("<rect").count() < 2_000,
        "{} rects",
        svg.matches("<rect").count()
    );
}

/// Every text of a figure's SVG with its size in points at the SVG's physical width: the root
/// gives `width="…mm"` and a `viewBox`, each `<text>` its `font-size` in user units.
fn text_sizes_pt(svg: &str) -> Vec<(f64, String)> {
    let attr = |tag: &str, name: &str| -> Option<String> {
        let pat = format!(" {name}=\"");
        let i = tag.find(&pat)? + pat.len();
        Some(tag[i..].split('"').next()?.to_string())
    };
    let root = &svg[svg.find("<svg").expect("root")..];
    let root = &root[..root.find('>').expect("root end")];
    let width_mm: f64 = attr(root, "width")
        .and_then(|w| w.strip_suffix("mm").map(str::to_string))
        .expect("width in mm")
        .parse()
        .expect("number");
    let view_w: f64 = attr(root, "viewBox")
        .and_then(|v| v.split_whitespace().nth(2).map(str::to_string))
        .expect("viewBox")
        .parse()
        .expect("number");
    let pt_per_user = width_mm / 25.4 * 72.0 / view_w;
    svg.split("<text ")
        .skip(1)
        .map(|t| {
            let size: f64 = attr(t, "font-size").expect("font-size").parse().expect("number");
            let text = t.split('>').skip(1).collect::<Vec<_>>().join(">");
            let plain: String = text
                .split('<')
                .map(|p| p.split('>').next_back().unwrap_or(""))
                .collect();
            (size * pt_per_user, plain)
        })
        .collect()
}

/// Issue 34: every scene's figure at its default print size (90 mm for one panel, 190 mm for
/// more) renders every text at 6 pt or more at that width (sub- and superscripts are 70 % of
/// their text, as in TeX), axis titles at 8 pt and tick labels at 7 pt.
#[test]
fn every_text_is_at_least_6_pt_at_the_declared_width() {
    let mut failures = Vec::new();
    for (id, fig) in quick_figures() {
        let svg = adhesion::render::plot::svg_string(fig).expect("svg");
        let sizes = text_sizes_pt(&svg);
        assert!(!sizes.is_empty(), "{id}: no text");
        for (pt, text) in &sizes {
            if *pt < 6.0 - 0.05 {
                failures.push(format!("{id}: {pt:.2} pt: {text}"));
            }
        }
        // Axis titles of 8 pt and tick labels of 7 pt are there.
        for want in [8.0, 7.0] {
            if !sizes.iter().any(|(pt, _)| (pt - want).abs() < 0.05) {
                failures.push(format!("{id}: no text at {want} pt"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every label a figure draws: axis titles, panel headings, series, marker and region names,
/// marker labels, field names, notes.
fn labels(fig: &Figure) -> Vec<String> {
    let mut out = vec![fig.title.clone()];
    out.extend(fig.notes.iter().cloned());
    for p in &fig.panels {
        out.extend([p.x.title(), p.y.title(), p.label.clone(), p.title.clone()]);
        out.extend(p.series.iter().map(|s| s.name.clone()));
        out.extend(p.markers.iter().map(|m| m.name.clone()));
        out.extend(p.markers.iter().filter_map(|m| m.label.clone()));
        out.extend(p.regions.iter().map(|r| r.name.clone()));
        out.extend(p.notes.iter().cloned());
        if let Some(f) = &p.field {
            out.push(f.name.clone());
            out.extend(f.highlight.iter().map(|h| h.1.clone()));
        }
    }
    out
}

/// Issue 34: no label of any scene shows the brackets of a broken sub- or superscript group
/// (`ζ₍₀²E₎*/w`, `k₍eσ²₎`, `R₍f²₎`): every bare script word is of one kind of character (no
/// superscript digit, no Latin letter next to a Greek one inside a subscript), nothing is left
/// in e-notation, and no `ζ0`, `Z0` or baseline asterisk of a modulus remains in the notation.
#[test]
fn labels_of_every_scene_group_their_scripts() {
    use adhesion::render::text::{Script, notation, parse, terminal};
    let mut failures = Vec::new();
    for (id, fig) in quick_figures() {
        for label in labels(fig) {
            let shown = notation(&label);
            let term = terminal(&shown);
            if term.contains(['₍', '₎']) {
                failures.push(format!("{id}: bracketed group in {term:?} ({label:?})"));
            }
            for run in parse(&shown) {
                let greek = run.text.chars().any(|c| ('\u{0370}'..='\u{03FF}').contains(&c));
                let latin = run.text.chars().any(|c| c.is_ascii_alphabetic());
                let sup_digit = run.text.chars().any(|c| "⁰¹²³⁴⁵⁶⁷⁸⁹".contains(c));
                if run.script == Script::Sub && ((greek && latin) || sup_digit) {
                    failures.push(format!("{id}: subscript {:?} in {label:?}", run.text));
                }
                if run.script == Script::Normal
                    && (run.text.contains("ζ0") || run.text.contains("E*") || run.text.contains("Z0 "))
                {
                    failures.push(format!("{id}: {:?} left in {label:?}", run.text));
                }
            }
            let plain = adhesion::render::text::plain(&shown);
            if plain
                .split(|c: char| c.is_whitespace() || c == ',' || c == ';' || c == '(' || c == ')')
                .any(|w| {
                    let w = w.trim_end_matches(['.', ':']);
                    w.contains('e') && w.parse::<f64>().is_ok() && !w.chars().all(|c| c.is_alphabetic())
                })
            {
                failures.push(format!("{id}: e-notation in {plain:?}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The text of a PDF as a reader's text extraction finds it: the glyphs shown (`Tj`) in every
/// content stream, each mapped to Unicode through the `ToUnicode` map of the font selected
/// (`Tf`) at that point. Enough of the format for the renderer's PDFs (pdf-writer objects,
/// Flate streams, Identity-H fonts with two-byte codes).
fn pdf_text(pdf: &[u8]) -> String {
    use std::collections::HashMap;
    use std::io::Read;
    let find = |hay: &[u8], pat: &[u8], from: usize| {
        hay.get(from..)?
            .windows(pat.len())
            .position(|w| w == pat)
            .map(|p| p + from)
    };
    // Objects: number -> (dictionary text, inflated stream).
    let mut objects: HashMap<u32, (String, Vec<u8>)> = HashMap::new();
    let mut at = 0;
    while let Some(start) = find(pdf, b" 0 obj", at) {
        let num_start = pdf[..start]
            .iter()
            .rposition(|b| !b.is_ascii_digit())
            .map_or(0, |p| p + 1);
        let num: u32 = std::str::from_utf8(&pdf[num_start..start])
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(0);
        let end = find(pdf, b"endobj", start).expect("endobj");
        let body = &pdf[start + 6..end];
        let (dict, stream) = match find(body, b"stream", 0) {
            Some(s) => {
                let mut data_start = s + 6;
                while matches!(body[data_start], b'\r' | b'\n') {
                    data_start += 1;
                }
                let data_end = find(body, b"endstream", data_start).expect("endstream");
                let raw = &body[data_start..data_end];
                let dict = String::from_utf8_lossy(&body[..s]).into_owned();
                let data = if dict.contains("/FlateDecode") {
                    let mut out = Vec::new();
                    flate2::read::ZlibDecoder::new(raw)
                        .read_to_end(&mut out)
                        .map(|_| out)
                        .unwrap_or_default()
                } else {
                    raw.to_vec()
                };
                (dict, data)
            }
            None => (String::from_utf8_lossy(body).into_owned(), Vec::new()),
        };
        objects.insert(num, (dict, stream));
        at = end;
    }
    let reference = |dict: &str, key: &str| -> Option<u32> {
        let i = dict.find(key)? + key.len();
        dict[i..].split_whitespace().next()?.parse().ok()
    };
    // Font resource names -> ToUnicode maps (code -> text).
    let mut maps: HashMap<String, HashMap<u16, String>> = HashMap::new();
    for (dict, _) in objects.values() {
        let Some(i) = dict.find("/Font <<").or_else(|| dict.find("/Font<<")) else {
            continue;
        };
        let fonts = &dict[i + 6..];
        let fonts = &fonts[fonts.find("<<").expect("dict") + 2..fonts.find(">>").expect("dict end")];
        let words: Vec<&str> = fonts.split_whitespace().collect();
        for w in words.windows(4) {
            let (Some(name), Ok(obj), "R") = (w[0].strip_prefix('/'), w[1].parse::<u32>(), w[3]) else {
                continue;
            };
            let Some(cmap) = objects
                .get(&obj)
                .and_then(|(d, _)| reference(d, "/ToUnicode"))
                .and_then(|c| objects.get(&c))
            else {
                continue;
            };
            let text = String::from_utf8_lossy(&cmap.1);
            let mut map = HashMap::new();
            for block in text.split("beginbfchar").skip(1) {
                let block = block.split("endbfchar").next().unwrap_or("");
                let hex: Vec<&str> = block
                    .split(['<', '>'])
                    .map(str::trim)
                    .filter(|s| !s.is_empty())
                    .collect();
                for pair in hex.chunks(2) {
                    if let [code, uni] = pair
                        && let Ok(code) = u16::from_str_radix(code, 16)
                    {
                        let units: Vec<u16> = (0..uni.len() / 4)
                            .filter_map(|k| u16::from_str_radix(&uni[4 * k..4 * k + 4], 16).ok())
                            .collect();
                        map.insert(code, String::from_utf16_lossy(&units));
                    }
                }
            }
            maps.insert(name.to_string(), map);
        }
    }
    // Content: `/name size Tf` selects a font, `(..) Tj` shows two-byte codes.
    let mut out = String::new();
    for (_, stream) in objects.values() {
        let mut font = String::new();
        let mut i = 0;
        while i < stream.len() {
            match stream[i] {
                b'/' => {
                    let end = (i + 1..stream.len())
                        .find(|&k| !stream[k].is_ascii_alphanumeric())
                        .unwrap_or(stream.len());
                    let name = String::from_utf8_lossy(&stream[i + 1..end]).into_owned();
                    let rest = &stream[end..(end + 24).min(stream.len())];
                    if String::from_utf8_lossy(rest).split_whitespace().nth(1) == Some("Tf") {
                        font = name;
                    }
                    i = end;
                }
                b'(' => {
                    let mut bytes = Vec::new();
                    let mut k = i + 1;
                    while k < stream.len() && stream[k] != b')' {
                        if stream[k] == b'\\' && k + 1 < stream.len() {
                            k += 1;
                            let c = stream[k];
                            if c.is_ascii_digit() {
                                let mut v = 0u32;
                                let mut n = 0;
                                while n < 3 && k < stream.len() && (b'0'..=b'7').contains(&stream[k]) {
                                    v = v * 8 + u32::from(stream[k] - b'0');
                                    k += 1;
                                    n += 1;
                                }
                                bytes.push(v as u8);
                                continue;
                            }
                            bytes.push(match c {
                                b'n' => b'\n',
                                b'r' => b'\r',
                                b't' => b'\t',
                                b'b' => 8,
                                b'f' => 12,
                                other => other,
                            });
                        } else {
                            bytes.push(stream[k]);
                        }
                        k += 1;
                    }
                    if let Some(map) = maps.get(&font) {
                        for c in bytes.chunks(2) {
                            if let [a, b] = c
                                && let Some(t) = map.get(&(u16::from(*a) << 8 | u16::from(*b)))
                            {
                                out.push_str(t);
                            }
                        }
                    }
                    i = k + 1;
                }
                _ => i += 1,
            }
        }
        out.push('\n');
    }
    out
}

/// Issue 34: `--format pdf` writes the figure as a PDF whose labels are text (a reader's text
/// extraction finds the axis titles, tick labels and legend), with the font embedded, on a
/// page of the figure's physical size.
#[test]
fn pdf_export_keeps_the_labels_as_text_with_the_font_embedded() {
    let (_, fig) = quick_figures()
        .iter()
        .find(|(id, _)| *id == "fig2.4")
        .expect("fig2.4");
    let print = adhesion::render::plot::Print::default();
    let pdf = adhesion::render::pdf::pdf_bytes_at(fig, &print).expect("pdf");
    assert!(pdf.starts_with(b"%PDF-"));
    let raw = String::from_utf8_lossy(&pdf);
    assert!(raw.contains("/FontFile2"), "the font is embedded");
    assert!(raw.contains("DejaVuSans"));
    // The page is 190 mm wide (538.6 pt).
    let media = raw.split("/MediaBox [").nth(1).expect("MediaBox");
    let w: f64 = media
        .split_whitespace()
        .nth(2)
        .expect("width")
        .parse()
        .expect("number");
    assert!((w - 190.0 / 25.4 * 72.0).abs() < 1.0, "page {w} pt wide");
    // Compared on letters and digits: accents are combining marks in the PDF's text.
    let letters = |t: &str| -> String { t.chars().filter(|c| c.is_alphanumeric()).collect() };
    let text = letters(&pdf_text(&pdf));
    for panel in &fig.panels {
        for title in [panel.x.title(), panel.y.title()] {
            let plain = letters(&adhesion::render::text::plain(&adhesion::render::text::notation(
                &title,
            )));
            assert!(text.contains(&plain), "{plain:?} not in the PDF's text:\n{text}");
        }
    }
}

/// Where a text writes a number as Rust's `{:e}` does (`1.5e-9`, `2E+3`) or with an ASCII
/// hyphen for its minus sign (`-2.08`, `(-4`, `=-1`), rather than as the figures' number
/// formatter (`adhesion::figure::number`) writes it (`−2.08 × 10⁻⁴`). A hyphen between two
/// numbers or words (`1-3 nm`, `(2.34)-(2.36)`, `n = 9-11`) is a range or a compound, not a
/// sign.
fn misprinted_numbers(text: &str) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let mut found = Vec::new();
    let around = |i: usize| -> String {
        chars[i.saturating_sub(12)..(i + 12).min(chars.len())]
            .iter()
            .collect()
    };
    for i in 0..chars.len() {
        let digit = |k: usize| chars.get(k).is_some_and(char::is_ascii_digit);
        // e-notation: a digit, e or E, an optional sign, a digit.
        if digit(i) && matches!(chars.get(i + 1), Some('e' | 'E')) {
            let k = i + 2 + usize::from(matches!(chars.get(i + 2), Some('-' | '+' | '−')));
            if digit(k) {
                found.push(format!("e-notation in …{}…", around(i)));
            }
        }
        // A hyphen as a minus sign: at the start or after a space, bracket or relation.
        if chars[i] == '-' && digit(i + 1) && (i == 0 || " ([=<>,;:".contains(chars[i - 1])) {
            found.push(format!("ASCII hyphen as minus in …{}…", around(i)));
        }
    }
    found
}

#[test]
fn misprinted_numbers_are_found_and_ranges_are_not() {
    for bad in ["h/R = -2.08e-4", "tolerance 1.5e-9", "2E+3 points", "loss (-4.1)"] {
        assert!(!misprinted_numbers(bad).is_empty(), "{bad}");
    }
    for good in [
        "h/R = −2.08 × 10⁻⁴",
        "1-3 nm",
        "Eqs. (2.34)-(2.36)",
        "n = 9-11",
        "fig4.5e",
        "P/(2E*R²)",
        "Gauss-Legendre",
        "C6 = 3, C12 = 1",
    ] {
        assert_eq!(misprinted_numbers(good), Vec::<String>::new(), "{good}");
    }
}

/// Every text a quick figure draws (title, notes, panel headings, axis titles, legends, marker
/// and field names) and every scene's caption writes its numbers as the figures' formatter
/// does: no e-notation, no ASCII hyphen for a minus sign. The quick-form note is exempt: it
/// lists the changed parameters as a preset writes them (`depth_over_radius = 1e-4`), and the
/// full figure does not carry it.
#[test]
fn figure_texts_print_numbers_as_print_does() {
    let mut failures = Vec::new();
    for (id, fig) in quick_figures() {
        for label in labels(fig) {
            if label.starts_with("quick form: ") {
                continue;
            }
            for f in misprinted_numbers(&label) {
                failures.push(format!("{id}: {f} in {label:?}"));
            }
        }
    }
    for s in scenes::all() {
        let info = s.info();
        for f in misprinted_numbers(info.caption) {
            failures.push(format!("{} caption: {f}", info.id));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
