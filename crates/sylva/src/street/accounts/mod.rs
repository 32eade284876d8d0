//! Money, on top of the other rooms: the account's items (`items`: each benefit and cost's key,
//! label, colour and who pays), prices and costs, carbon, aesthetics, survival, the
//! pruning cycles carried out on the grown tree and priced (`pruner`), a year's account and its
//! table, i-Tree's tables and the typical position, the site model calibrated against them,
//! and published figures to hold them to.

pub mod aesthetics;
pub mod calibrate;
pub mod carbon;
pub mod costs;
pub mod items;
pub mod itree;
pub mod ledger;
pub mod money;
pub mod prices;
pub mod pruner;
pub mod published;
pub mod records;
pub mod survival;
pub mod table;
pub mod typical;
