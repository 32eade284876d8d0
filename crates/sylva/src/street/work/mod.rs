//! The street's own work: where the tree runs into its site, the pruning regime that answers
//! it, and the wire model against the database's records. It reads the site and the crown
//! (`energy::crown`); the cycles carried out and priced are the accounts' (`accounts::pruner`).

pub mod conflicts;
pub mod pruning;
pub mod wires;
