//! Named choices (methods, precisions, traversals, visibility and erf modes): one lookup
//! from a name to the value, shared by every `FromStr` of the library.

/// Finds the option in `all` whose `name` is `s`, or says which names were expected
/// (the `FromStr` of the CLI's named choices).
pub fn parse_by_name<T: Copy>(
    s: &str,
    all: &[T],
    name: fn(T) -> &'static str,
    what: &str,
) -> std::result::Result<T, String> {
    all.iter().copied().find(|&m| name(m) == s).ok_or_else(|| {
        let names: Vec<_> = all.iter().map(|&m| name(m)).collect();
        format!(
            "unknown {what} `{s}` (expected one of: {})",
            names.join(", ")
        )
    })
}
