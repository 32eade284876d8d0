//! Mutations of valid inputs: numbers swapped for hostile values, lines cut, doubled, swapped
//! or dropped, bytes that are not text, files cut short.

use crate::harness::Rng;

/// Values that break careless parsers and unbounded loops.
pub const HOSTILE: [&str; 22] = [
    "NaN",
    "nan",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e-320",
    "-1",
    "0",
    "-0",
    "1e9",
    "4294967296",
    "99999999999999999999",
    "",
    "abc",
    "1.5",
    "0x10",
    "--1",
    "1e",
    "+",
    "3.4028236e38",
    "2147483648",
];

/// Byte ranges of the numbers in `text`.
fn numbers(text: &[u8]) -> Vec<(usize, usize)> {
    let mut found = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let starts = text[i].is_ascii_digit()
            || (text[i] == b'-' && text.get(i + 1).is_some_and(u8::is_ascii_digit));
        if starts && (i == 0 || !text[i - 1].is_ascii_alphanumeric()) {
            let mut j = i + 1;
            while j < text.len() && (text[j].is_ascii_digit() || b".eE-+".contains(&text[j])) {
                j += 1;
            }
            found.push((i, j));
            i = j;
        } else {
            i += 1;
        }
    }
    found
}

fn lines(text: &[u8]) -> Vec<Vec<u8>> {
    text.split_inclusive(|&b| b == b'\n')
        .map(<[u8]>::to_vec)
        .collect()
}

/// One to three random mutations of `text`.
pub fn mutate(rng: &mut Rng, text: &[u8]) -> Vec<u8> {
    let mut out = text.to_vec();
    for _ in 0..1 + rng.below(3) {
        out = once(rng, &out);
    }
    out
}

fn once(rng: &mut Rng, text: &[u8]) -> Vec<u8> {
    let mut out = text.to_vec();
    match rng.below(9) {
        // A number replaced by a hostile value (the most telling mutation: twice as likely).
        0..=2 => {
            let spans = numbers(&out);
            if let Some(&(a, b)) = spans.get(rng.below(spans.len())) {
                let value = rng.pick(&HOSTILE).as_bytes();
                out.splice(a..b, value.iter().copied());
            }
        }
        // Cut short.
        3 => out.truncate(rng.below(out.len() + 1)),
        // A line dropped, doubled or swapped with another.
        4..=6 => {
            let mut l = lines(&out);
            if !l.is_empty() {
                let i = rng.below(l.len());
                match rng.below(3) {
                    0 => {
                        l.remove(i);
                    }
                    1 => {
                        let copy = l[i].clone();
                        l.insert(i, copy);
                    }
                    _ => {
                        let j = rng.below(l.len());
                        l.swap(i, j);
                    }
                }
            }
            out = l.concat();
        }
        // Bytes that are not text, or not this format.
        7 => {
            let at = rng.below(out.len() + 1);
            const JUNK: [&[u8]; 8] = [
                b"\xff\xfe\x00",
                b"\"",
                b"[[",
                b"<",
                b"=",
                b",,,",
                b"\n\n",
                b"\0",
            ];
            let junk = *rng.pick(&JUNK);
            out.splice(at..at, junk.iter().copied());
        }
        // A number made enormous in place: many digits more.
        _ => {
            let spans = numbers(&out);
            if let Some(&(_, b)) = spans.get(rng.below(spans.len())) {
                out.splice(b..b, b"000000".iter().copied());
            }
        }
    }
    out
}

/// A damaged binary file (a GLB): bytes flipped, a length rewritten, or cut short.
pub fn damage(rng: &mut Rng, bytes: &[u8]) -> Vec<u8> {
    let mut out = bytes.to_vec();
    match rng.below(4) {
        0 => out.truncate(rng.below(out.len() + 1)),
        1 => {
            for _ in 0..1 + rng.below(16) {
                let i = rng.below(out.len());
                out[i] ^= 1 << rng.below(8);
            }
        }
        2 => {
            // The header's or a chunk's length word.
            let at = *rng.pick(&[8usize, 12, 20]);
            if out.len() >= at + 4 {
                let v = rng.pick(&[0u32, 1, 0x7fff_ffff, 0xffff_ffff]).to_le_bytes();
                out[at..at + 4].copy_from_slice(&v);
            }
        }
        _ => {
            // The JSON chunk mutated as text (accessor counts, offsets, indices).
            let json_len = out
                .get(12..16)
                .map_or(0, |b| u32::from_le_bytes(b.try_into().unwrap()) as usize);
            if json_len > 0 && out.len() >= 20 + json_len {
                let json = out[20..20 + json_len].to_vec();
                let mut m = mutate(rng, &json);
                // Keep the chunk's length (pad or cut) so the damage stays inside the JSON.
                m.resize(json_len, b' ');
                out[20..20 + json_len].copy_from_slice(&m);
            }
        }
    }
    out
}
