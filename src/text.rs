//! Numbers and user text as one-line messages show them: at most 6 significant digits, control
//! characters escaped, long values cut. The error type ([`crate::error`]), the parameters and the
//! models format what they echo here, so that every message reads the same way.

/// Format a number for messages and the form: shortest text that round-trips.
pub fn fmt_value(x: f64) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    format!("{x}")
}

/// Text from the user as a message shows it: control characters escaped (`\n`, `\r`, `\t`,
/// `\0`, `\u{1b}`), and cut after `max_chars` characters with a note of the full length, so
/// that an echoed value never breaks the one-line message or floods the terminal.
pub fn escape_for_message(text: &str, max_chars: usize) -> String {
    let mut out = String::new();
    for (n, c) in text.chars().enumerate() {
        if n == max_chars {
            out.push_str(&format!("… ({} characters)", text.chars().count()));
            break;
        }
        match c {
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '\0' => out.push_str("\\0"),
            c if c.is_control() || c == '\u{feff}' => out.push_str(&format!("\\u{{{:x}}}", c as u32)),
            c => out.push(c),
        }
    }
    out
}

/// A value echoed in a message: a float as [`fmt_sig`] (not the hundreds of digits of a huge
/// one), anything else as [`escape_for_message`] (at most 80 characters).
pub fn echo_value(text: &str) -> String {
    let t = text.trim();
    if (t.len() > 12 || t.contains(['.', 'e', 'E']))
        && let Ok(x) = t.parse::<f64>()
    {
        return fmt_sig(x);
    }
    escape_for_message(text, 80)
}

/// A number for messages with at most 6 significant digits: plain for moderate magnitudes,
/// scientific otherwise (`1.23457e-9`), `NaN`, `inf` and `-inf` as such.
pub fn fmt_sig(x: f64) -> String {
    fn trim(m: &str) -> &str {
        if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.')
        } else {
            m
        }
    }
    if !x.is_finite() {
        return fmt_value(x);
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (1e-3..1e6).contains(&a) {
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        // A carry on rounding (999999.7 -> 1000000) only adds a trailing zero.
        return trim(&format!("{x:.decimals$}")).to_string();
    }
    let t = format!("{x:.5e}");
    match t.split_once('e') {
        Some((m, e)) => format!("{}e{e}", trim(m)),
        None => t,
    }
}

/// A message with every long number in it (more than 10 digits, like the hundreds of digits
/// of `{}` on 1e300) rewritten by [`fmt_sig`]; identifiers such as `fig3.8` and short numbers
/// stay as they are.
pub fn compact_numbers(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_digit() || (b[i] == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit));
        let after_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_' || b[i - 1] == b'.');
        if !starts || after_word {
            let c = text[i..].chars().next().unwrap_or(' ');
            out.push(c);
            i += c.len_utf8();
            continue;
        }
        let mut j = i + usize::from(b[i] == b'-');
        let mut digits = 0;
        let mut seen_dot = false;
        while j < b.len() && (b[j].is_ascii_digit() || (b[j] == b'.' && !seen_dot)) {
            seen_dot |= b[j] == b'.';
            digits += usize::from(b[j].is_ascii_digit());
            j += 1;
        }
        if j < b.len() && (b[j] == b'e' || b[j] == b'E') {
            let mut k = j + 1;
            if k < b.len() && (b[k] == b'-' || b[k] == b'+') {
                k += 1;
            }
            if k < b.len() && b[k].is_ascii_digit() {
                while k < b.len() && b[k].is_ascii_digit() {
                    k += 1;
                }
                j = k;
            }
        }
        let token = text[i..j].trim_end_matches('.');
        let end = i + token.len();
        match token.parse::<f64>() {
            Ok(x) if digits > 10 => out.push_str(&fmt_sig(x)),
            _ => out.push_str(token),
        }
        i = end;
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn message_numbers_have_at_most_six_significant_digits() {
        use super::fmt_sig;
        assert_eq!(fmt_sig(4.710_337_979_759_895e24), "4.71034e24");
        assert_eq!(fmt_sig(1.465_612_345), "1.46561");
        assert_eq!(fmt_sig(-1e-9), "-1e-9");
        assert_eq!(fmt_sig(0.25), "0.25");
        assert_eq!(fmt_sig(123_456.78), "123457");
        assert_eq!(fmt_sig(f64::INFINITY), "inf");
        assert_eq!(fmt_sig(f64::NAN), "NaN");
        assert_eq!(fmt_sig(0.0), "0");
        assert_eq!(fmt_sig(f64::MAX), "1.79769e308");
        assert_eq!(super::echo_value(&format!("{}", 1e300)), "1e300");
        assert_eq!(super::echo_value("1.4656123456789012"), "1.46561");
        assert_eq!(
            super::escape_for_message("a\r\nb\0\u{1b}[2J", 80),
            "a\\r\\nb\\0\\u{1b}[2J"
        );
        let long = "x".repeat(5_000_000);
        assert_eq!(
            super::escape_for_message(&long, 10),
            "xxxxxxxxxx… (5000000 characters)"
        );
    }
}
