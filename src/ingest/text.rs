//! What every text input shares before it is parsed.

/// `bytes` without the UTF-8 byte-order mark that some editors and exporters write first (read
/// as text, it would glue itself to the first word: an OBJ's first `v` would be skipped).
pub(crate) fn without_byte_order_mark(bytes: &[u8]) -> &[u8] {
    bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes)
}
