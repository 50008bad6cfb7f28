//! Enumeration types: a name, a description and items numbered 1, 2, ... in order.

/// One item of an enumeration type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EnumerationItem {
    pub name: &'static str,
    pub description: &'static str,
}

/// An enumeration type of the description (its type definitions).
#[derive(Debug)]
pub struct EnumerationType {
    pub name: &'static str,
    pub description: &'static str,
    /// The items in code order, from the core's name list.
    pub items: fn() -> Vec<EnumerationItem>,
}

impl PartialEq for EnumerationType {
    /// Types are identified by their name (unique in a description).
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl EnumerationType {
    /// The items; item `i` (0-based) has the value `i + 1`.
    pub fn items(&self) -> Vec<EnumerationItem> {
        (self.items)()
    }

    /// The largest code (the number of items).
    pub fn max_code(&self) -> i32 {
        i32::try_from(self.items().len()).unwrap_or(i32::MAX)
    }

    /// "1 = ffr, 2 = segments, ...", every item, for the description of an Integer twin.
    pub fn codes_text(&self) -> String {
        let items: Vec<String> = self
            .items()
            .iter()
            .enumerate()
            .map(|(i, item)| format!("{} = {}", i + 1, item.name))
            .collect();
        items.join(", ")
    }

    /// The description of the Integer twin of the Enumeration parameter `name`.
    pub fn twin_description(&self, name: &str) -> String {
        format!(
            "{name} as an Integer, for importers that ignore Enumeration variables: {}. The same parameter as {name}: setting either sets both, the last value set wins",
            self.codes_text()
        )
    }

    /// "1 (ffr), 2 (segments), ...", every item, for messages and descriptions.
    pub fn allowed_text(&self) -> String {
        let items: Vec<String> = self
            .items()
            .iter()
            .enumerate()
            .map(|(i, item)| format!("{} ({})", i + 1, item.name))
            .collect();
        items.join(", ")
    }
}
