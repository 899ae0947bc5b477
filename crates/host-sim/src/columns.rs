//! Text for a terminal in fixed-width columns: words wrapped within a
//! column, a word wider than its column cut across lines, so that no line
//! passes its width and columns never run into each other.

/// The width the timelines keep within (columns of a terminal).
pub const TERMINAL: usize = 120;

/// `words` in lines of at most `width` characters, one space between
/// words; a word longer than `width` is cut into pieces of `width`. No
/// words: no lines.
pub fn wrap<S: AsRef<str>>(words: &[S], width: usize) -> Vec<String> {
    let width = width.max(1);
    let mut lines = Vec::new();
    let mut line = String::new();
    let mut used = 0;
    for word in words {
        let chars: Vec<char> = word.as_ref().chars().collect();
        for piece in chars.chunks(width) {
            let n = piece.len();
            if used > 0 && used + 1 + n > width {
                lines.push(std::mem::take(&mut line));
                used = 0;
            }
            if used > 0 {
                line.push(' ');
                used += 1;
            }
            line.extend(piece);
            used += n;
        }
    }
    if used > 0 {
        lines.push(line);
    }
    lines
}

/// A row of cells side by side, each cell `(lines, width)` padded to its
/// width, cells two spaces apart, as many lines as the tallest cell
/// (trailing spaces trimmed).
pub fn row(cells: &[(Vec<String>, usize)]) -> Vec<String> {
    let height = cells.iter().map(|(l, _)| l.len()).max().unwrap_or(0);
    (0..height)
        .map(|k| {
            let mut line = String::new();
            for (n, (lines, width)) in cells.iter().enumerate() {
                if n > 0 {
                    line.push_str("  ");
                }
                let text = lines.get(k).map_or("", String::as_str);
                line.push_str(text);
                let pad = width.saturating_sub(text.chars().count());
                line.push_str(&" ".repeat(pad));
            }
            line.trim_end().to_owned()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_wrap_within_the_width_and_long_words_are_cut() {
        assert_eq!(wrap(&["ab", "cd", "ef"], 5), ["ab cd", "ef"]);
        assert_eq!(wrap(&["abcdefgh"], 3), ["abc", "def", "gh"]);
        assert!(wrap::<&str>(&[], 4).is_empty());
    }

    #[test]
    fn cells_side_by_side_keep_their_columns() {
        let lines = row(&[
            (vec!["1.00s".into()], 6),
            (wrap(&["aaa", "bbb"], 4), 4),
            (vec!["20°C".into()], 4),
        ]);
        assert_eq!(lines, ["1.00s   aaa   20°C", "        bbb"]);
    }
}
