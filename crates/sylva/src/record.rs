//! Output records: every figure Sylva writes as JSON is a serde type in the library
//! (`street::records`, `weber_penn::made::TreeRecord`, `growth::survey::sweep::SweepRecord`,
//! ...), so the CLI's `--json`, the planners' page and the Python wheel give the same shape.

/// Any record as a JSON value. Its objects keep their keys in alphabetical order (serde_json's
/// map without `preserve_order`), as every Sylva JSON writes them, whatever the order of a
/// type's fields.
pub fn to_json<T: serde::Serialize>(record: &T) -> serde_json::Value {
    // Records hold numbers, strings, options, lists and maps with string keys only:
    // serialising them cannot fail.
    serde_json::to_value(record).expect("a record serialises")
}
