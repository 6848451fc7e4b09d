//! Java `.properties` files (ISO-8859-1 text of `key=value` lines), as JPK writes its headers.

use std::collections::HashMap;

/// Parse a properties file into its key-value pairs in file order: `#` and `!` comment lines,
/// `=`, `:` or white space between key and value, backslash escapes (`\t`, `\n`, `\r`, `\f`,
/// `\uXXXX`, any other character as itself) and lines continued by a final backslash.
pub(crate) fn parse(bytes: &[u8]) -> Vec<(String, String)> {
    let text = super::text::latin1(bytes);
    let natural = super::text::lines(&text);
    let mut out = Vec::new();
    let mut i = 0;
    while i < natural.len() {
        let first = natural[i].trim_start_matches([' ', '\t', '\x0c']);
        i += 1;
        if first.is_empty() || first.starts_with('#') || first.starts_with('!') {
            continue;
        }
        let mut logical = String::from(first);
        while ends_with_odd_backslashes(&logical) {
            logical.pop();
            if i >= natural.len() {
                break;
            }
            logical.push_str(natural[i].trim_start_matches([' ', '\t', '\x0c']));
            i += 1;
        }
        out.push(split(&logical));
    }
    out
}

/// Parse into a map (a later key replaces an earlier one, as in Java).
pub(crate) fn parse_map(bytes: &[u8]) -> HashMap<String, String> {
    parse(bytes).into_iter().collect()
}

fn ends_with_odd_backslashes(s: &str) -> bool {
    s.bytes().rev().take_while(|&b| b == b'\\').count() % 2 == 1
}

/// Split a logical line into its unescaped key and value.
fn split(line: &str) -> (String, String) {
    let chars: Vec<char> = line.chars().collect();
    let mut k = 0;
    while k < chars.len() {
        match chars[k] {
            '\\' => k += 2,
            '=' | ':' | ' ' | '\t' | '\x0c' => break,
            _ => k += 1,
        }
    }
    let key_end = k.min(chars.len());
    let mut v = key_end;
    while v < chars.len() && matches!(chars[v], ' ' | '\t' | '\x0c') {
        v += 1;
    }
    if v < chars.len() && matches!(chars[v], '=' | ':') {
        v += 1;
        while v < chars.len() && matches!(chars[v], ' ' | '\t' | '\x0c') {
            v += 1;
        }
    }
    (
        unescape(&chars[..key_end]),
        unescape(&chars[v.min(chars.len())..]),
    )
}

fn unescape(chars: &[char]) -> String {
    let mut out = String::with_capacity(chars.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        i += 1;
        if c != '\\' {
            out.push(c);
            continue;
        }
        let Some(&e) = chars.get(i) else { break };
        i += 1;
        match e {
            't' => out.push('\t'),
            'n' => out.push('\n'),
            'r' => out.push('\r'),
            'f' => out.push('\x0c'),
            'u' => {
                let hex: String = chars[i..chars.len().min(i + 4)].iter().collect();
                match u32::from_str_radix(&hex, 16)
                    .ok()
                    .filter(|_| hex.len() == 4)
                    .and_then(char::from_u32)
                {
                    Some(u) => {
                        out.push(u);
                        i += 4;
                    }
                    None => out.push('u'),
                }
            }
            other => out.push(other),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_separators_and_continuations() {
        let p = parse_map(
            b"#comment\n! also\nkey=value\na\\:b : c\\:d\n  spaced   value here\ncont=one \\\n    two\nu=\\u00b5m\nempty=\n",
        );
        assert_eq!(p["key"], "value");
        assert_eq!(p["a:b"], "c:d");
        assert_eq!(p["spaced"], "value here");
        assert_eq!(p["cont"], "one two");
        assert_eq!(p["u"], "\u{b5}m");
        assert_eq!(p["empty"], "");
        assert_eq!(p.len(), 6);
    }
}
