//! The CSV form both fits read (BRDF samples, observed light curves): a header line, then
//! one row a line; blank lines and lines starting with `#` are skipped.

use crate::scene::ValidationError;

/// The header line of `text` and its data rows, each with its line number (1-based) and
/// trimmed. With no header at all the error names `field` and says `empty`.
pub fn header_and_rows<'a>(
    text: &'a str,
    field: &str,
    empty: &str,
) -> Result<(&'a str, impl Iterator<Item = (usize, &'a str)>), ValidationError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((_, header)) = lines.next() else {
        return Err(ValidationError::new(field, empty));
    };
    Ok((header, lines))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_blank_lines_are_skipped_and_lines_keep_their_numbers() {
        let (header, rows) =
            header_and_rows("# made by hand\n\n a,b \n1,2\n#x\n3,4\n", "f", "e").unwrap();
        assert_eq!(header, "a,b");
        assert_eq!(rows.collect::<Vec<_>>(), vec![(4, "1,2"), (6, "3,4")]);
        let e = header_and_rows("# nothing\n", "samples", "no header")
            .err()
            .unwrap();
        assert_eq!(
            (e.field.as_str(), e.message.as_str()),
            ("samples", "no header")
        );
    }
}
