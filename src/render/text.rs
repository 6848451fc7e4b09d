//! Text of the figures: a small math markup for labels and its layout with the embedded font.
//!
//! The markup is the subset of TeX's math that axis labels and legends use, as matplotlib's
//! mathtext does for journals:
//!
//! ```text
//! σ_rms, h_o, P_{max}     subscript: one word after `_`, or the braced group
//! m^4, 2^-7, E^{*}        superscript: an optional sign and one word after `^`, or the group
//! \bar{d}, \hat{P}        overbar and hat over the group (also the combining marks U+0304, U+0302)
//! \alpha, \sigma, \Pi     Greek letters by name (Unicode letters work directly)
//! ```
//!
//! A word is a run of letters and digits. Everything else is plain text, so a label without
//! markup prints as written.
//!
//! [`layout`] places the glyphs with the font's advances and its kerning table (DejaVu Sans,
//! embedded); the PNG renderer rasterises them with anti-aliased coverage, the SVG renderer
//! writes `<tspan>` elements with a baseline shift and leaves the glyphs to the viewer.

use std::sync::OnceLock;

use ab_glyph::{Font, FontRef, GlyphId, PxScale, ScaleFont, point};

/// Vertical position of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Script {
    /// On the baseline.
    Normal,
    /// Lowered and smaller.
    Sub,
    /// Raised and smaller.
    Super,
}

/// A mark over a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Accent {
    /// None.
    None,
    /// A bar over the run (mean, normalised variable).
    Bar,
    /// A hat over the run.
    Hat,
}

/// A piece of text with one position and one accent.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Run {
    /// The characters, without markup.
    pub text: String,
    /// Baseline position.
    pub script: Script,
    /// Mark over the run.
    pub accent: Accent,
}

/// Height of a line of plain text above its baseline, in units of the text size (labels are
/// aligned on it, so that texts with and without scripts share their baseline).
pub const ASCENT: f64 = 0.8;
/// Depth of a line of plain text below its baseline, in units of the text size.
pub const DESCENT: f64 = 0.22;

/// Size of sub- and superscripts relative to the text.
pub const SCRIPT_SIZE: f64 = 0.7;
/// Shift of a subscript below the baseline, in units of the text size.
pub const SUB_SHIFT: f64 = 0.22;
/// Shift of a superscript above the baseline, in units of the text size.
pub const SUPER_SHIFT: f64 = 0.36;

const GREEK: &[(&str, char)] = &[
    ("alpha", 'α'),
    ("beta", 'β'),
    ("gamma", 'γ'),
    ("delta", 'δ'),
    ("epsilon", 'ε'),
    ("zeta", 'ζ'),
    ("eta", 'η'),
    ("theta", 'θ'),
    ("kappa", 'κ'),
    ("lambda", 'λ'),
    ("mu", 'μ'),
    ("nu", 'ν'),
    ("xi", 'ξ'),
    ("pi", 'π'),
    ("rho", 'ρ'),
    ("sigma", 'σ'),
    ("tau", 'τ'),
    ("phi", 'φ'),
    ("chi", 'χ'),
    ("psi", 'ψ'),
    ("omega", 'ω'),
    ("Gamma", 'Γ'),
    ("Delta", 'Δ'),
    ("Theta", 'Θ'),
    ("Lambda", 'Λ'),
    ("Pi", 'Π'),
    ("Sigma", 'Σ'),
    ("Phi", 'Φ'),
    ("Psi", 'Ψ'),
    ("Omega", 'Ω'),
    ("ell", 'ℓ'),
    ("partial", '∂'),
    ("infty", '∞'),
];

const COMBINING_HAT: char = '\u{0302}';
const COMBINING_BAR: char = '\u{0304}';
const COMBINING_OVERLINE: char = '\u{0305}';

/// Numbers in a label written as in print: e-notation as a power of ten (`1.25e-4` →
/// `1.25 × 10^{−4}`, `1e-5` → `10^{−5}`, the mantissa's digits kept) and a zero written with
/// decimals (`0.0000`, `0.00`) as `0`. A number is a run of digits with an optional point,
/// standing alone (not part of a word such as `fig4.5` or `2E*`).
pub fn numbers(src: &str) -> String {
    let chars: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    let joined = |c: char| c.is_alphanumeric() || matches!(c, '_' | '.' | '^' | '{' | '\\');
    while i < chars.len() {
        let c = chars[i];
        let starts = c.is_ascii_digit() && (i == 0 || !joined(chars[i - 1]));
        if !starts {
            out.push(c);
            i += 1;
            continue;
        }
        let mut j = i;
        while j < chars.len() && chars[j].is_ascii_digit() {
            j += 1;
        }
        if j + 1 < chars.len() && chars[j] == '.' && chars[j + 1].is_ascii_digit() {
            j += 1;
            while j < chars.len() && chars[j].is_ascii_digit() {
                j += 1;
            }
        }
        let mantissa: String = chars[i..j].iter().collect();
        // An exponent: e or E, an optional sign, digits, then no letter or digit.
        let mut k = j;
        let mut exponent = None;
        if k < chars.len() && matches!(chars[k], 'e' | 'E') {
            k += 1;
            let negative = k < chars.len() && matches!(chars[k], '-' | '−');
            if k < chars.len() && matches!(chars[k], '-' | '−' | '+') {
                k += 1;
            }
            let d0 = k;
            while k < chars.len() && chars[k].is_ascii_digit() {
                k += 1;
            }
            let free = ends_number(&chars, k);
            if k > d0 && free {
                let digits: String = chars[d0..k].iter().collect();
                let digits = digits.trim_start_matches('0');
                exponent = Some(if digits.is_empty() {
                    "0".to_string()
                } else if negative {
                    format!("−{digits}")
                } else {
                    digits.to_string()
                });
            }
        }
        let free = ends_number(&chars, j);
        match exponent {
            Some(e) if e == "0" => {
                out.push_str(&mantissa);
                i = k;
            }
            Some(e) if mantissa == "1" => {
                out.push_str(&format!("10^{{{e}}}"));
                i = k;
            }
            Some(e) => {
                out.push_str(&format!("{mantissa} × 10^{{{e}}}"));
                i = k;
            }
            None if free && mantissa.contains('.') && mantissa.chars().all(|c| c == '0' || c == '.') => {
                out.push('0');
                i = j;
            }
            None => {
                out.push_str(&mantissa);
                i = j;
            }
        }
    }
    out
}

/// Whether a number ends before `chars[k]`: the end of the text, or a character that is not a
/// letter, a digit, or a point before a digit (a full stop ends a number).
fn ends_number(chars: &[char], k: usize) -> bool {
    match chars.get(k) {
        None => true,
        Some('.') => !chars.get(k + 1).is_some_and(char::is_ascii_digit),
        Some(c) => !c.is_alphanumeric(),
    }
}

/// The kind of a character that may continue a bare sub- or superscript word: ASCII digits,
/// Greek letters and other letters are three kinds; anything else (superscript digits, signs,
/// brackets) ends the word.
fn word_kind(c: char) -> Option<u8> {
    if c.is_ascii_digit() {
        Some(0)
    } else if ('\u{0370}'..='\u{03FF}').contains(&c) {
        Some(2)
    } else if c.is_alphabetic() {
        Some(1)
    } else {
        None
    }
}

/// The project's notation applied to a label before it is laid out in a figure: numbers as
/// [`numbers`] writes them, `ζ0` and `Z0` as ζ₀ and Z₀, the asterisk of an effective modulus (`E*`, `μ_T*`) as a superscript, and the
/// energy loss `H` as ℋ, as the dissertation writes them (a standalone `H`: a letter of a
/// longer word stays). Markup already explicit (`ζ_0`, `E^{*}`) is kept.
pub fn notation(src: &str) -> String {
    let src = numbers(src);
    let chars: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len() + 8);
    let alnum = |k: Option<&char>| k.is_some_and(|c| c.is_alphanumeric() || *c == '_');
    for (i, &c) in chars.iter().enumerate() {
        let prev = i.checked_sub(1).and_then(|k| chars.get(k));
        let next = chars.get(i + 1);
        match c {
            // ζ after a letter is a product (`Rζ0`); Z after a letter is part of a word.
            '0' if (prev == Some(&'ζ')
                || (prev == Some(&'Z') && !alnum(i.checked_sub(2).and_then(|k| chars.get(k)))))
                && !next.is_some_and(|n| n.is_ascii_digit() || n.is_alphabetic() || *n == '_') =>
            {
                out.push_str("_0");
            }
            '*' if prev.is_some_and(|p| p.is_alphabetic()) && !matches!(prev, Some('{' | '^')) => {
                out.push_str("^*");
            }
            'H' if !alnum(prev) && prev != Some(&'\\') && !alnum(next) && next != Some(&'^') => {
                out.push('ℋ');
            }
            _ => out.push(c),
        }
    }
    out
}

/// Parse the markup into runs (adjacent runs of one kind merged).
pub fn parse(src: &str) -> Vec<Run> {
    let chars: Vec<char> = src.chars().collect();
    let mut runs: Vec<Run> = Vec::new();
    parse_into(&chars, Script::Normal, Accent::None, &mut runs);
    // Merge neighbours of one kind.
    let mut out: Vec<Run> = Vec::new();
    for r in runs {
        if r.text.is_empty() {
            continue;
        }
        match out.last_mut() {
            Some(last) if last.script == r.script && last.accent == r.accent && r.accent == Accent::None => {
                last.text.push_str(&r.text);
            }
            _ => out.push(r),
        }
    }
    out
}

/// The braced group starting at `chars[i] == '{'`: its contents and the index after it.
fn group(chars: &[char], i: usize) -> (Vec<char>, usize) {
    let mut depth = 0;
    for (k, &c) in chars.iter().enumerate().skip(i) {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return (chars[i + 1..k].to_vec(), k + 1);
                }
            }
            _ => {}
        }
    }
    (chars[i + 1..].to_vec(), chars.len())
}

fn push(runs: &mut Vec<Run>, c: char, script: Script, accent: Accent) {
    match runs.last_mut() {
        Some(last) if last.script == script && last.accent == accent => last.text.push(c),
        _ => runs.push(Run {
            text: c.to_string(),
            script,
            accent,
        }),
    }
}

fn parse_into(chars: &[char], script: Script, accent: Accent, runs: &mut Vec<Run>) {
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        match c {
            '_' | '^' if script == Script::Normal && i + 1 < chars.len() => {
                let inner = if c == '_' { Script::Sub } else { Script::Super };
                if chars[i + 1] == '{' {
                    let (g, next) = group(chars, i + 1);
                    parse_into(&g, inner, accent, runs);
                    i = next;
                } else {
                    let mut j = i + 1;
                    if c == '^' && matches!(chars[j], '-' | '+' | '−') {
                        j += 1;
                    }
                    // A word of one kind (Latin letters, Greek letters or digits: `k_eσ²` is
                    // k with the subscript e before σ², `ζ_0²` ζ₀ squared), or a single
                    // non-space character (`E^*`).
                    let start = j;
                    let kind = chars.get(j).copied().and_then(word_kind);
                    while j < chars.len() && kind.is_some() && word_kind(chars[j]) == kind {
                        j += 1;
                    }
                    if j == start && j < chars.len() && !chars[j].is_whitespace() {
                        j += 1;
                    }
                    if j == i + 1 {
                        push(runs, c, script, accent);
                        i += 1;
                        continue;
                    }
                    for &d in &chars[i + 1..j] {
                        let d = if d == '-' { '−' } else { d };
                        push(runs, d, inner, accent);
                    }
                    i = j;
                }
            }
            '\\' if chars
                .get(i + 1)
                .is_some_and(|n| matches!(n, '_' | '^' | '\\' | '{' | '}')) =>
            {
                // An escaped markup character, e.g. in a parameter's name (see [`escape`]).
                push(runs, chars[i + 1], script, accent);
                i += 2;
            }
            '\\' => {
                let mut j = i + 1;
                while j < chars.len() && chars[j].is_ascii_alphabetic() {
                    j += 1;
                }
                let name: String = chars[i + 1..j].iter().collect();
                let acc = match name.as_str() {
                    "bar" | "overline" => Some(Accent::Bar),
                    "hat" => Some(Accent::Hat),
                    _ => None,
                };
                if let Some(acc) = acc {
                    if j < chars.len() && chars[j] == '{' {
                        let (g, next) = group(chars, j);
                        parse_into(&g, script, acc, runs);
                        i = next;
                    } else if j < chars.len() {
                        parse_into(&chars[j..=j], script, acc, runs);
                        i = j + 1;
                    } else {
                        i = j;
                    }
                } else if let Some((_, g)) = GREEK.iter().find(|(n, _)| *n == name) {
                    push(runs, *g, script, accent);
                    i = j;
                } else {
                    push(runs, '\\', script, accent);
                    i += 1;
                }
            }
            COMBINING_HAT | COMBINING_BAR | COMBINING_OVERLINE => {
                // A combining mark accents the character before it.
                let acc = if c == COMBINING_HAT {
                    Accent::Hat
                } else {
                    Accent::Bar
                };
                if let Some(last) = runs.last_mut()
                    && let Some(prev) = last.text.pop()
                {
                    let sc = last.script;
                    if last.text.is_empty() {
                        runs.pop();
                    }
                    runs.push(Run {
                        text: prev.to_string(),
                        script: sc,
                        accent: acc,
                    });
                }
                i += 1;
            }
            _ => {
                push(runs, c, script, accent);
                i += 1;
            }
        }
    }
}

/// `text` as markup that reads as written: `_`, `^`, `\`, `{` and `}` escaped with a backslash
/// (identifiers such as parameter names in legends).
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if matches!(c, '_' | '^' | '\\' | '{' | '}') {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

/// The plain text of the markup (accents dropped), e.g. for width estimates of fallbacks.
pub fn plain(src: &str) -> String {
    parse(src).into_iter().map(|r| r.text).collect()
}

/// The markup as a terminal shows it: scripts in Unicode sub- and superscript letters where
/// every character of the run has one (`m^4` → `m⁴`, `h_o` → `hₒ`), else after a `_` or `^`
/// without braces (`P_{adh}` → `P_adh`); bars and hats as combining marks on a one-letter run.
pub fn terminal(src: &str) -> String {
    const SUB: (&str, &str) = (
        "0123456789+-−=()aehijklmnoprstuvx",
        "₀₁₂₃₄₅₆₇₈₉₊₋₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ",
    );
    const SUPER: (&str, &str) = (
        "0123456789+-−=()*abcdefghijklmnoprstuvwxyzABDEGHIJKLMNOPRTUVW",
        "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁻⁼⁽⁾*ᵃᵇᶜᵈᵉᶠᵍʰⁱʲᵏˡᵐⁿᵒᵖʳˢᵗᵘᵛʷˣʸᶻᴬᴮᴰᴱᴳᴴᴵᴶᴷᴸᴹᴺᴼᴾᴿᵀᵁⱽᵂ",
    );
    let map = |text: &str, (from, to): (&str, &str)| -> Option<String> {
        text.chars()
            .map(|c| from.chars().position(|f| f == c).and_then(|k| to.chars().nth(k)))
            .collect()
    };
    let mut out = String::new();
    for run in parse(src) {
        let text = match run.accent {
            Accent::Bar if run.text.chars().count() == 1 => format!("{}\u{304}", run.text),
            Accent::Hat if run.text.chars().count() == 1 => format!("{}\u{302}", run.text),
            _ => run.text,
        };
        match run.script {
            Script::Normal => out.push_str(&text),
            Script::Sub => out.push_str(&map(&text, SUB).unwrap_or_else(|| format!("_{text}"))),
            Script::Super => out.push_str(&map(&text, SUPER).unwrap_or_else(|| format!("^{text}"))),
        }
    }
    out
}

/// The embedded fonts (regular, bold).
fn fonts() -> &'static [FontRef<'static>; 2] {
    static FONTS: OnceLock<[FontRef<'static>; 2]> = OnceLock::new();
    FONTS.get_or_init(|| {
        [
            FontRef::try_from_slice(dejavu::sans::regular()).expect("DejaVu Sans is valid TrueType"),
            FontRef::try_from_slice(dejavu::sans::bold()).expect("DejaVu Sans Bold is valid TrueType"),
        ]
    })
}

/// The pair-kerning lookups of the `kern` feature of a font's GPOS table.
struct GposKern {
    face: ttf_parser::Face<'static>,
    lookups: Vec<u16>,
}

fn gpos_kerns() -> &'static [Option<GposKern>; 2] {
    static KERNS: OnceLock<[Option<GposKern>; 2]> = OnceLock::new();
    KERNS.get_or_init(|| {
        let load = |data: &'static [u8]| {
            let face = ttf_parser::Face::parse(data, 0).ok()?;
            let gpos = face.tables().gpos?;
            let kern = ttf_parser::Tag::from_bytes(b"kern");
            let mut lookups: Vec<u16> = Vec::new();
            for f in gpos.features {
                if f.tag == kern {
                    for i in f.lookup_indices {
                        if !lookups.contains(&i) {
                            lookups.push(i);
                        }
                    }
                }
            }
            Some(GposKern { face, lookups })
        };
        [load(dejavu::sans::regular()), load(dejavu::sans::bold())]
    })
}

/// Horizontal pair adjustment of `a` followed by `b` from the GPOS `kern` feature, in font
/// units (0 where the font gives none).
fn gpos_kern(bold: bool, a: GlyphId, b: GlyphId) -> f64 {
    use ttf_parser::gpos::{PairAdjustment, PositioningSubtable};
    let Some(k) = &gpos_kerns()[usize::from(bold)] else {
        return 0.0;
    };
    let Some(gpos) = k.face.tables().gpos else {
        return 0.0;
    };
    let (a, b) = (ttf_parser::GlyphId(a.0), ttf_parser::GlyphId(b.0));
    for &li in &k.lookups {
        let Some(lookup) = gpos.lookups.get(li) else {
            continue;
        };
        for sub in lookup.subtables.into_iter::<PositioningSubtable>() {
            let PositioningSubtable::Pair(pair) = sub else {
                continue;
            };
            let Some(ci) = pair.coverage().get(a) else {
                continue;
            };
            let found = match pair {
                PairAdjustment::Format1 { sets, .. } => sets.get(ci).and_then(|s| s.get(b)),
                PairAdjustment::Format2 { classes, matrix, .. } => {
                    matrix.get((classes.0.get(a), classes.1.get(b)))
                }
            };
            if let Some((first, _)) = found {
                return f64::from(first.x_advance);
            }
        }
    }
    0.0
}

/// One glyph placed in text coordinates: x to the right of the text's origin, y down from its
/// baseline.
#[derive(Debug, Clone, Copy)]
pub struct Placed {
    /// The glyph.
    pub id: GlyphId,
    /// Pen position x (px).
    pub x: f64,
    /// Baseline y (px, positive down).
    pub y: f64,
    /// Size (px).
    pub size: f64,
}

/// A mark drawn over a span of glyphs: kind, x range and the y of its foot (px).
#[derive(Debug, Clone, Copy)]
pub struct Mark {
    /// Bar or hat.
    pub accent: Accent,
    /// Left end.
    pub x0: f64,
    /// Right end.
    pub x1: f64,
    /// y of the mark (px, positive down; above the glyphs).
    pub y: f64,
    /// Size of the text it sits on (px).
    pub size: f64,
}

/// Laid-out text: glyphs, accent marks, width and vertical extent.
#[derive(Debug, Clone)]
pub struct Layout {
    /// The glyphs.
    pub glyphs: Vec<Placed>,
    /// The accent marks.
    pub marks: Vec<Mark>,
    /// Advance width (px).
    pub width: f64,
    /// Height above the baseline (px, positive).
    pub ascent: f64,
    /// Depth below the baseline (px, positive).
    pub descent: f64,
    /// Bold face.
    pub bold: bool,
}

/// Lay out markup at `size` px: advances plus the font's kerning between neighbours of one run.
pub fn layout(src: &str, size: f64, bold: bool) -> Layout {
    let font = &fonts()[usize::from(bold)];
    let mut glyphs = Vec::new();
    let mut marks = Vec::new();
    let mut x = 0.0;
    let base = font.as_scaled(PxScale::from(size as f32));
    let asc = f64::from(base.ascent());
    let mut ascent = ASCENT * size;
    let mut descent = DESCENT * size;
    for run in parse(&notation(src)) {
        let (sz, dy) = match run.script {
            Script::Normal => (size, 0.0),
            Script::Sub => (size * SCRIPT_SIZE, SUB_SHIFT * size),
            Script::Super => (size * SCRIPT_SIZE, -SUPER_SHIFT * size),
        };
        let scaled = font.as_scaled(PxScale::from(sz as f32));
        let x_start = x;
        let mut prev: Option<GlyphId> = None;
        let mut top = f64::INFINITY;
        for c in run.text.chars() {
            let id = scaled.glyph_id(c);
            if let Some(p) = prev {
                // The legacy `kern` table where it has the pair, else GPOS.
                let legacy = f64::from(scaled.kern(p, id));
                x += if legacy == 0.0 {
                    gpos_kern(bold, p, id) * f64::from(scaled.h_scale_factor())
                } else {
                    legacy
                };
            }
            glyphs.push(Placed {
                id,
                x,
                y: dy,
                size: sz,
            });
            if let Some(o) = scaled.outline_glyph(id.with_scale_and_position(sz as f32, point(0.0, 0.0))) {
                top = top.min(f64::from(o.px_bounds().min.y) + dy);
            }
            x += f64::from(scaled.h_advance(id));
            prev = Some(id);
        }
        if !top.is_finite() {
            top = dy - 0.7 * sz;
        }
        ascent = ascent.max(-dy + 0.75 * sz);
        descent = descent.max(dy + 0.22 * sz);
        if run.accent != Accent::None {
            let y = top - 0.12 * sz;
            marks.push(Mark {
                accent: run.accent,
                x0: x_start + 0.08 * sz,
                x1: x - 0.08 * sz,
                y,
                size: sz,
            });
            ascent = ascent.max(-y + 0.2 * sz);
        }
    }
    let _ = asc;
    Layout {
        glyphs,
        marks,
        width: x,
        ascent,
        descent,
        bold,
    }
}

/// Width of the markup at `size` px.
pub fn width(src: &str, size: f64, bold: bool) -> f64 {
    layout(src, size, bold).width
}

/// Sum of the glyph advances of `text` without kerning (for comparison with [`width`]).
pub fn advance_sum(text: &str, size: f64) -> f64 {
    let scaled = fonts()[0].as_scaled(PxScale::from(size as f32));
    text.chars()
        .map(|c| f64::from(scaled.h_advance(scaled.glyph_id(c))))
        .sum()
}

/// Anti-aliased coverage of the laid-out text: calls `put(x, y, coverage)` for every covered
/// pixel, in text coordinates (origin at the left end of the baseline, y down), coverage in
/// (0, 1].
pub fn rasterize(l: &Layout, mut put: impl FnMut(f64, f64, f64)) {
    let font = &fonts()[usize::from(l.bold)];
    for g in &l.glyphs {
        let glyph = g.id.with_scale_and_position(g.size as f32, point(0.0, 0.0));
        if let Some(o) = font.outline_glyph(glyph) {
            let b = o.px_bounds();
            // Sub-pixel pen positions are folded into the raster origin.
            let ox = g.x + f64::from(b.min.x);
            let oy = g.y + f64::from(b.min.y);
            o.draw(|px, py, c| {
                if c > 0.0 {
                    put(ox + f64::from(px), oy + f64::from(py), f64::from(c.min(1.0)));
                }
            });
        }
    }
    for m in &l.marks {
        let t = (0.07 * m.size).max(1.0);
        match m.accent {
            Accent::Bar => {
                let mut x = m.x0.floor();
                while x <= m.x1 {
                    let mut y = (m.y - t).floor();
                    while y <= m.y {
                        put(x, y, 1.0);
                        y += 1.0;
                    }
                    x += 1.0;
                }
            }
            Accent::Hat => {
                // A caret: two strokes meeting above the middle.
                let mid = 0.5 * (m.x0 + m.x1);
                let half = (0.5 * (m.x1 - m.x0)).clamp(0.2 * m.size, 0.3 * m.size);
                let h = 0.22 * m.size;
                let n = (4.0 * half).ceil().max(2.0) as usize;
                for k in 0..=n {
                    let u = k as f64 / n as f64;
                    for (x, y) in [
                        (mid - half + u * half, m.y - u * h),
                        (mid + half - u * half, m.y - u * h),
                    ] {
                        let mut dy = 0.0;
                        while dy < t {
                            put(x.floor(), (y - dy).floor(), 1.0);
                            dy += 1.0;
                        }
                    }
                }
            }
            Accent::None => {}
        }
    }
}

/// Escape text for SVG and HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The markup in the project's notation ([`notation`]) as tagged text: each run's characters
/// (accents as combining marks after each character), escaped for XML, wrapped by `tag`
/// according to the run's position.
fn tagged(src: &str, tag: impl Fn(Script, &str) -> String) -> String {
    let mut out = String::new();
    for run in parse(&notation(src)) {
        let mut text = String::new();
        for c in run.text.chars() {
            text.push(c);
            match run.accent {
                Accent::Bar => text.push(COMBINING_BAR),
                Accent::Hat => text.push(COMBINING_HAT),
                Accent::None => {}
            }
        }
        out.push_str(&tag(run.script, &esc(&text)));
    }
    out
}

/// The markup as SVG `<tspan>`s: sub- and superscripts with `baseline-shift` and a smaller
/// size, accents as combining marks after each character (placed by the viewer's font).
pub fn svg_tspans(src: &str) -> String {
    tagged(src, |script, text| match script {
        Script::Normal => format!("<tspan>{text}</tspan>"),
        Script::Sub => format!(
            "<tspan baseline-shift=\"-{:.0}%\" font-size=\"{:.0}%\">{text}</tspan>",
            SUB_SHIFT * 100.0 / SCRIPT_SIZE,
            SCRIPT_SIZE * 100.0
        ),
        Script::Super => format!(
            "<tspan baseline-shift=\"{:.0}%\" font-size=\"{:.0}%\">{text}</tspan>",
            SUPER_SHIFT * 100.0 / SCRIPT_SIZE,
            SCRIPT_SIZE * 100.0
        ),
    })
}

/// The markup as HTML: sub- and superscripts as `<sub>` and `<sup>`, accents as combining
/// marks, text escaped.
pub fn html(src: &str) -> String {
    tagged(src, |script, text| match script {
        Script::Normal => text.to_string(),
        Script::Sub => format!("<sub>{text}</sub>"),
        Script::Super => format!("<sup>{text}</sup>"),
    })
}

/// Greek letters written out in ASCII prose (`mu_T`, `pi w R`, `sigma`) as the letters, where
/// the name stands alone (not part of a longer word).
pub fn greek_words(src: &str) -> String {
    const NAMES: [(&str, &str); 13] = [
        ("alpha", "α"),
        ("beta", "β"),
        ("gamma", "γ"),
        ("Delta", "Δ"),
        ("zeta", "ζ"),
        ("theta", "θ"),
        ("lambda", "λ"),
        ("mu", "μ"),
        ("pi", "π"),
        ("sigma", "σ"),
        ("phi", "φ"),
        ("chi", "χ"),
        ("ell", "ℓ"),
    ];
    let mut out = String::with_capacity(src.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        match NAMES.iter().find(|(n, _)| *n == word.as_str()) {
            Some((_, g)) => out.push_str(g),
            None => out.push_str(word),
        }
        word.clear();
    };
    for c in src.chars() {
        if c.is_ascii_alphabetic() {
            word.push(c);
        } else {
            flush(&mut word, &mut out);
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bare_script_words_stop_where_the_kind_of_character_changes() {
        // The defects of the issue: "ζ₍₀²E₎*/w", "k₍eσ²₎", "R₍f²₎".
        let scripts = |src: &str| -> Vec<(String, Script)> {
            parse(&notation(src))
                .into_iter()
                .filter(|r| r.script != Script::Normal)
                .map(|r| (r.text, r.script))
                .collect()
        };
        assert_eq!(
            scripts("b = ζ_0²E*/w"),
            vec![("0".into(), Script::Sub), ("*".into(), Script::Super)]
        );
        assert_eq!(
            scripts("k_eσ²/(cwA_e)"),
            vec![("e".into(), Script::Sub), ("e".into(), Script::Sub)]
        );
        assert_eq!(scripts("k_f l_f/(π R_f² E)").len(), 3);
        assert!(scripts("R_f²").iter().all(|(t, _)| t == "f"));
        assert_eq!(scripts("σ_rms"), vec![("rms".into(), Script::Sub)]);
        assert_eq!(terminal("k_eσ²"), "kₑσ²");
    }

    #[test]
    fn notation_subscripts_zeta0_and_raises_the_asterisk() {
        assert_eq!(notation("z_c/ζ0, √(2Rζ0)"), "z_c/ζ_0, √(2Rζ_0)");
        assert_eq!(notation("Z0 [nm]"), "Z_0 [nm]");
        assert_eq!(notation("ζ_0 and Z01 and fig3.Z0x"), "ζ_0 and Z01 and fig3.Z0x");
        assert_eq!(notation("H/(2E*R³)"), "ℋ/(2E^*R³)");
        assert_eq!(
            notation("μ_T* = 2, E^{*} kept, HHV"),
            "μ_T^* = 2, E^{*} kept, HHV"
        );
        assert_eq!(notation("2 * 3"), "2 * 3");
    }

    #[test]
    fn numbers_drop_e_notation_and_empty_decimals() {
        assert_eq!(
            numbers("tol 1.25e-4 and 3e5"),
            "tol 1.25 × 10^{−4} and 3 × 10^{5}"
        );
        assert_eq!(numbers("1e-5 ζ0"), "10^{−5} ζ0");
        assert_eq!(numbers("A/λ = 0.0000, h = 0.00 nm"), "A/λ = 0, h = 0 nm");
        // Not numbers of their own: ids, moduli, words.
        assert_eq!(numbers("fig4.5 2E*R 1e5x k_e2"), "fig4.5 2E*R 1e5x k_e2");
        assert_eq!(numbers("0.50 and 2.0e+00"), "0.50 and 2.0");
        assert_eq!(plain(&notation("1.5e-3")), "1.5 × 10−3");
    }

    #[test]
    fn captions_become_html_with_greek_letters() {
        assert_eq!(
            html(&greek_words("P_adh/(pi w R), mu_T < 1 & more")),
            "P<sub>adh</sub>/(π w R), μ<sub>T</sub> &lt; 1 &amp; more"
        );
        assert_eq!(greek_words("mutual pi"), "mutual π");
    }

    fn kinds(src: &str) -> Vec<(String, Script, Accent)> {
        parse(src)
            .into_iter()
            .map(|r| (r.text, r.script, r.accent))
            .collect()
    }

    #[test]
    fn words_after_underscore_and_caret_are_scripts() {
        assert_eq!(
            kinds("σ_rms/h_o"),
            vec![
                ("σ".into(), Script::Normal, Accent::None),
                ("rms".into(), Script::Sub, Accent::None),
                ("/h".into(), Script::Normal, Accent::None),
                ("o".into(), Script::Sub, Accent::None),
            ]
        );
        assert_eq!(kinds("2^-7")[1], ("−7".into(), Script::Super, Accent::None));
        assert_eq!(kinds("E^{*} [Pa]")[1], ("*".into(), Script::Super, Accent::None));
        assert_eq!(kinds("a_{x y}")[1], ("x y".into(), Script::Sub, Accent::None));
    }

    #[test]
    fn terminal_text_uses_unicode_scripts_where_every_letter_has_one() {
        assert_eq!(terminal("σ_rms/h_o"), "σᵣₘₛ/hₒ");
        assert_eq!(terminal("P_{adh}/(πwR)"), "P_adh/(πwR)");
        assert_eq!(terminal("H/(2E^{*}R^3)"), "H/(2E*R³)");
        assert_eq!(terminal("m^4 2^-7"), "m⁴ 2⁻⁷");
        assert_eq!(terminal("\\bar{d} = d"), "d\u{304} = d");
        assert_eq!(terminal("plain text [nm]"), "plain text [nm]");
        let name = "max_depth_norm = 2^10 {a} \\b";
        assert_eq!(terminal(&escape(name)), name);
        assert_eq!(plain(&escape(name)), name);
    }

    #[test]
    fn accents_from_commands_and_combining_marks() {
        assert_eq!(kinds("P/P\u{0302}")[1], ("P".into(), Script::Normal, Accent::Hat));
        assert_eq!(kinds("\\bar{d}")[0], ("d".into(), Script::Normal, Accent::Bar));
        assert_eq!(plain("\\alpha = 1"), "α = 1");
        assert_eq!(plain("snake_case_"), "snakecase_");
    }

    #[test]
    fn kerning_narrows_av_and_to_and_leaves_dmt_at_its_advances() {
        for text in ["AV", "To", "Ty"] {
            let w = width(text, 100.0, false);
            let sum = advance_sum(text, 100.0);
            assert!(w < sum - 1.0, "{text}: kerned {w} vs advances {sum}");
        }
        // DejaVu Sans has no kerning pair in "DMT" (neither in `kern` nor in GPOS): the glyphs
        // sit at their advances, without the gap the per-glyph rounding of the old text path left.
        let w = width("DMT", 100.0, false);
        assert!((w - advance_sum("DMT", 100.0)).abs() < 1e-9, "{w}");
    }
}
