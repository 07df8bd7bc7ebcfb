//! A STEP file's bytes as the text of its exchange structure (ISO 10303-21).
//!
//! The standard's alphabet is ISO 8859-1 printable characters; anything else inside a string is
//! written with the control directives `\X\HH` (one ISO 8859-1 character) and `\X2\HHHH...\X0\`
//! (UCS-2). Exporters do not always follow it: SolidWorks and others write raw 8-bit bytes in
//! names (ISO 8859-1 or a Windows code page), newer ones write UTF-8. Readers downstream (our
//! statement scanner and truck-stepio) want plain ASCII, and truck-stepio also stops at a
//! comment before the first keyword. So the bytes are decoded (UTF-8 when they are valid UTF-8,
//! ISO 8859-1 otherwise: every byte is a character there, so no file is refused for its
//! encoding), comments are dropped, and every non-ASCII character inside a string is written
//! back as the standard's own directive, which keeps what the string means.
//!
//! Input: the file's bytes. Output: a `String` of ASCII characters outside strings' escapes
//! (non-ASCII characters outside strings are kept: they are an error the parser names).

use std::fmt::Write;

/// The exchange structure's text of a STEP file's bytes (see the module documentation).
pub fn exchange_text(bytes: &[u8]) -> String {
    match std::str::from_utf8(bytes) {
        Ok(text) => plain_text(text),
        Err(_) => plain_text(&bytes.iter().map(|&b| char::from(b)).collect::<String>()),
    }
}

/// Whether `bytes` open like a STEP file: `ISO-10303-21` after white space and comments.
pub fn looks_like_step(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(4096)];
    exchange_text(head).starts_with("ISO-10303-21")
}

/// `text` without comments and leading white space, with every non-ASCII character of a string
/// written as a control directive.
fn plain_text(text: &str) -> String {
    let mut plain = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match c {
            '\'' => {
                quoted = !quoted;
                plain.push(c);
            }
            '/' if !quoted && chars.peek() == Some(&'*') => {
                chars.next();
                let mut previous = ' ';
                for next in chars.by_ref() {
                    if previous == '*' && next == '/' {
                        break;
                    }
                    previous = next;
                }
                plain.push(' ');
            }
            _ if quoted && !c.is_ascii() => push_directive(&mut plain, c),
            _ => plain.push(c),
        }
    }
    plain.trim_start().to_string()
}

/// Writes `c` as `\X\HH` when it is in ISO 8859-1, else as `\X2\HHHH\X0\` (its UTF-16 units).
fn push_directive(text: &mut String, c: char) {
    let code = u32::from(c);
    if code <= 0xFF {
        let _ = write!(text, "\\X\\{code:02X}");
    } else {
        text.push_str("\\X2\\");
        for unit in c.encode_utf16(&mut [0; 2]) {
            let _ = write!(text, "{unit:04X}");
        }
        text.push_str("\\X0\\");
    }
}

#[cfg(test)]
mod tests {
    use crate::ingest::step::text::{exchange_text, looks_like_step};

    #[test]
    fn iso_8859_1_bytes_in_a_name_become_directives() {
        let text = exchange_text(b"#7=PRODUCT('Pi\xe8ce 1','',$);");
        assert_eq!(text, "#7=PRODUCT('Pi\\X\\E8ce 1','',$);");
    }

    #[test]
    fn utf_8_names_become_iso_8859_1_and_ucs_2_directives() {
        let text = exchange_text("#7=PRODUCT('Pièce Ω','',$);".as_bytes());
        assert_eq!(text, "#7=PRODUCT('Pi\\X\\E8ce \\X2\\03A9\\X0\\','',$);");
    }

    #[test]
    fn comments_go_but_comment_marks_inside_strings_stay() {
        let text = exchange_text(b"/* made by hand */ISO-10303-21;\n#1=A('/* not a comment */');");
        assert_eq!(text, "ISO-10303-21;\n#1=A('/* not a comment */');");
    }

    #[test]
    fn a_file_opening_with_a_comment_is_recognised() {
        assert!(looks_like_step(b"/* header */\r\nISO-10303-21;\nHEADER;"));
        assert!(!looks_like_step(b"solid cube\nfacet normal 0 0 1"));
    }

    #[test]
    fn a_doubled_quote_stays_inside_its_string() {
        let text = exchange_text(b"#1=A('it''s \xe9');/* x */#2=B();");
        assert_eq!(text, "#1=A('it''s \\X\\E9'); #2=B();");
    }
}
