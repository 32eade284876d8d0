//! Structural checks of a written tileset, since the official 3D Tiles validator cannot be
//! installed here: see [`check_tileset`].
