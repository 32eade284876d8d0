//! The handles and owners the `dxf` crate (0.6) leaves out of an R2000 file, put in after it
//! writes: AutoCAD discards a drawing whose tables have no handle ("Bad handle 0: already in
//! use", ixmilia/dxf-rs issue 85), and a reader that finds objects by handle must first repair
//! one whose ENDBLK repeats its BLOCK's (dxf-rs pull request 106). The pass works on the
//! written file's group codes, object by object (an object runs from one group code 0 to the
//! next), and adds only what is missing:
//!
//! - each TABLE head: a handle of its own (5) and its owner, none (330 0);
//! - each table's records: their table as owner;
//! - each BLOCK, ENDBLK and entity in a block: its BLOCK_RECORD as owner; each ENDBLK a handle
//!   of its own;
//! - each entity of the ENTITIES section: `*MODEL_SPACE`'s BLOCK_RECORD as owner;
//! - `$HANDSEED`: past every handle given.
//!
//! Once the crate writes these itself, this pass finds nothing to add.

use std::collections::HashMap;

/// One group code and its value, as written.
struct Pair<'a> {
    code: i32,
    value: &'a str,
}

/// `text` (an ASCII DXF as the crate writes it: CR LF line ends) with the handles and owners
/// above added. Text that is not a DXF's pairs of lines comes back unchanged.
pub fn complete(text: &str) -> String {
    let body = text.strip_suffix("\r\n").unwrap_or(text);
    let lines: Vec<&str> = body.split("\r\n").collect();
    if lines.len() % 2 == 1 {
        return text.to_string();
    }
    let mut pairs = Vec::with_capacity(lines.len() / 2);
    for two in lines.chunks_exact(2) {
        let Ok(code) = two[0].trim().parse::<i32>() else {
            return text.to_string();
        };
        pairs.push(Pair {
            code,
            value: two[1],
        });
    }
    let hex = |v: &str| u64::from_str_radix(v.trim(), 16).ok();
    // New handles start past every handle the file holds (5; 105 for DIMSTYLE records).
    let mut next = (pairs.iter())
        .filter(|p| p.code == 5 || p.code == 105)
        .filter_map(|p| hex(p.value))
        .max()
        .unwrap_or(0)
        + 1;
    let mut take = || {
        let h = format!("{next:X}");
        next += 1;
        h
    };
    // The BLOCK_RECORDs' handles by block name (they come before the blocks, in TABLES).
    let mut records: HashMap<String, String> = HashMap::new();
    let mut out: Vec<(i32, String)> = Vec::with_capacity(pairs.len() + pairs.len() / 8);
    let mut section = String::new();
    let mut owner = String::new();
    let mut start = 0;
    while start < pairs.len() {
        let end = (start + 1..pairs.len())
            .find(|&i| pairs[i].code == 0)
            .unwrap_or(pairs.len());
        let object = &pairs[start..end];
        let kind = object[0].value.trim();
        let find = |code: i32| object.iter().find(|p| p.code == code).map(|p| p.value);
        let has_owner = find(330).is_some();
        let mut handle = find(5).map(str::to_string);
        let mut add_handle = false;
        // The object's owner, added where it names none.
        let owned_by: Option<String> = match (section.as_str(), kind) {
            (_, "SECTION") => {
                section = find(2).unwrap_or("").trim().to_string();
                None
            }
            ("TABLES", "TABLE") => {
                if handle.is_none() {
                    handle = Some(take());
                    add_handle = true;
                }
                owner = handle.clone().unwrap_or_default();
                Some("0".into())
            }
            ("TABLES", "ENDTAB") | (_, "ENDSEC" | "EOF") => None,
            ("TABLES", record) => {
                if record == "BLOCK_RECORD"
                    && let (Some(name), Some(h)) = (find(2), &handle)
                {
                    records.insert(name.trim().to_ascii_uppercase(), h.clone());
                }
                Some(owner.clone())
            }
            ("BLOCKS", "BLOCK") => {
                let name = find(2).unwrap_or("").trim().to_ascii_uppercase();
                owner = records.get(&name).cloned().unwrap_or_default();
                Some(owner.clone())
            }
            ("BLOCKS", "ENDBLK") => {
                handle = Some(take());
                Some(owner.clone())
            }
            ("BLOCKS", _) => Some(owner.clone()),
            ("ENTITIES", _) => records.get("*MODEL_SPACE").cloned(),
            _ => None,
        };
        let add_owner = owned_by.filter(|o| !has_owner && !o.is_empty());
        for (i, p) in object.iter().enumerate() {
            // Only an ENDBLK's handle is replaced (it repeats its BLOCK's); every other is kept.
            match (p.code, kind, &handle) {
                (5, "ENDBLK", Some(h)) => out.push((5, h.clone())),
                _ => out.push((p.code, p.value.to_string())),
            }
            // A table's handle and owner follow its name; anything else's owner follows its
            // handle.
            let after_name = kind == "TABLE" && p.code == 2 && i == 1;
            if after_name && add_handle {
                out.push((5, handle.clone().unwrap_or_default()));
            }
            if ((p.code == 5 && !add_handle) || (after_name && add_handle))
                && let Some(o) = &add_owner
            {
                out.push((330, o.clone()));
            }
        }
        start = end;
    }
    // $HANDSEED (a header variable: its value is the pair after its name) past them all.
    if let Some(i) = out.iter().position(|p| p.0 == 9 && p.1 == "$HANDSEED")
        && let Some(seed) = out.get_mut(i + 1)
    {
        seed.1 = format!("{next:X}");
    }
    let mut text = String::with_capacity(text.len() + out.len() * 4);
    for (code, value) in out {
        text.push_str(&format!("{code:>3}\r\n{value}\r\n"));
    }
    text
}
