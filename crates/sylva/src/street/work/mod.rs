//! The street's own work: where the tree runs into its site, how close it comes to each
//! overhead line (`lines`), the chance its roots damage the pavement (`roots`), the pruning
//! regime that answers it, and the wire model against the database's records. It reads the site and the crown
//! (`energy::crown`); the cycles carried out and priced are the accounts' (`accounts::pruner`).

pub mod conflicts;
pub mod lines;
pub mod pruning;
pub mod roots;
pub mod wires;
