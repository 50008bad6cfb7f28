//! The XML writer the description's parts write into.

use quick_xml::Writer;

/// An indenting XML writer into memory.
pub(super) type W = Writer<Vec<u8>>;
