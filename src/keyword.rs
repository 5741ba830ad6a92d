//! Values a user names by a keyword (a flag's value, a scene file's string): each lists
//! every value with its name and one line about it, so that the command line, the scene
//! readers and the error messages take them from one place.

/// An enumeration named by keywords.
pub trait Keyword: Copy + PartialEq + Send + Sync + 'static {
    /// Every value, in the order they are listed.
    const ALL: &'static [Self];

    /// The keyword that names this value.
    fn name(self) -> &'static str;

    /// One line about this value.
    fn about(self) -> &'static str;

    /// The value `name` names.
    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|v| v.name() == name)
    }

    /// Every keyword, comma-separated (for error messages).
    fn names() -> String {
        Self::ALL
            .iter()
            .map(|v| v.name())
            .collect::<Vec<_>>()
            .join(", ")
    }
}
