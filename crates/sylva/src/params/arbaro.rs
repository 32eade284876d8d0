//! Import of Arbaro's XML species files:
//! `<arbaro><species name='...'><param name='Shape' value='7'/>...</species></arbaro>`.
//!
//! Parameter names are the paper's (plus Arbaro's additions, all in [`super::PARAMS`]); missing
//! parameters take Arbaro's defaults, unknown ones are an error, as in Arbaro. `LeafShape` is a
//! name in Arbaro and is mapped to Sylva's outline index with [`ARBARO_LEAF_SHAPES`].

use super::TreeParams;
use crate::error::ParamsError;
use quick_xml::events::{BytesStart, Event};

/// Arbaro leaf shape names and the Sylva `LeafShape` index each maps to. `discN` (any N) is a disc.
pub const ARBARO_LEAF_SHAPES: &[(&str, u32)] = &[
    ("0", 0),
    ("disc", 0),
    ("square", 6),
    ("palm", 7),
    ("sphere", 8),
];

fn leaf_shape_index(value: &str) -> Option<u32> {
    if let Some(&(_, i)) = ARBARO_LEAF_SHAPES.iter().find(|(n, _)| *n == value) {
        return Some(i);
    }
    if value
        .strip_prefix("disc")
        .is_some_and(|n| n.parse::<u32>().is_ok())
    {
        return Some(0);
    }
    value.parse::<u32>().ok().filter(|&i| i <= 8)
}

pub(crate) fn line_at(text: &str, byte: u64) -> usize {
    let end = (byte as usize).min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

fn attrs(e: &BytesStart, source: &str) -> Result<(Option<String>, Option<String>), String> {
    let mut name = None;
    let mut value = None;
    for attr in e.attributes() {
        let attr = attr.map_err(|err| format!("bad attribute: {err}"))?;
        let text = attr
            .normalized_value(quick_xml::XmlVersion::Implicit1_0)
            .map_err(|err| format!("bad attribute value in {source}: {err}"))?
            .into_owned();
        match attr.key.as_ref() {
            "name" => name = Some(text),
            "value" => value = Some(text),
            _ => {}
        }
    }
    Ok((name, value))
}

/// Reads an Arbaro XML species file's text; `source_name` goes into error messages.
pub fn from_arbaro_xml(text: &str, source_name: &str) -> Result<TreeParams, ParamsError> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut params = TreeParams {
        name: source_name.to_string(),
        description: format!("imported from Arbaro file {source_name}"),
        ..TreeParams::default()
    };
    let mut seen_species = false;
    let syntax = |line: usize, message: String| ParamsError::Syntax {
        source_name: format!("{source_name}, line {line}"),
        message,
    };
    loop {
        let pos = reader.buffer_position();
        let event = reader.read_event().map_err(|e| {
            syntax(
                line_at(text, reader.error_position()),
                format!("not valid XML: {e}"),
            )
        })?;
        let line = line_at(text, pos);
        match event {
            Event::Start(e) | Event::Empty(e) => {
                let (name, value) = attrs(&e, source_name).map_err(|m| syntax(line, m))?;
                match e.name().as_ref() {
                    "arbaro" => {}
                    "species" => {
                        seen_species = true;
                        if let Some(n) = name {
                            params.name = n;
                        }
                    }
                    "param" => {
                        let (Some(name), Some(value)) = (name, value) else {
                            return Err(syntax(
                                line,
                                "a <param> needs `name` and `value` attributes".into(),
                            ));
                        };
                        let place = format!("{source_name}, line {line}");
                        let number = if name == "LeafShape" {
                            leaf_shape_index(value.trim()).map(f64::from).ok_or_else(|| {
                                syntax(
                                    line,
                                    format!(
                                        "LeafShape `{value}` is not one of 0..8, disc, discN, square, palm, sphere"
                                    ),
                                )
                            })?
                        } else {
                            value.trim().parse::<f64>().map_err(|_| {
                                syntax(
                                    line,
                                    format!(
                                        "parameter `{name}` has value `{value}`, expected a number"
                                    ),
                                )
                            })?
                        };
                        params.set(&name, number).map_err(|e| e.at(place))?;
                    }
                    other => {
                        return Err(syntax(
                            line,
                            format!(
                                "unexpected element <{}>: expected <arbaro>, <species> or <param>",
                                other
                            ),
                        ));
                    }
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if !seen_species {
        return Err(ParamsError::Syntax {
            source_name: source_name.to_string(),
            message: "no <species> element: not an Arbaro species file".into(),
        });
    }
    clamp_variations(&mut params);
    params.validate().map_err(|e| e.at(source_name))?;
    Ok(params)
}

/// Arbaro accepts a variation larger than its base value (its `shave-grass.xml` has Scale 0.5,
/// ScaleV 0.7) and then fails on the trees whose size comes out negative. Sylva's own files
/// reject that; on import the variation is clamped to the base value, with a note.
fn clamp_variations(p: &mut TreeParams) {
    let mut notes = Vec::new();
    let pairs: [(f64, &mut f64, &str, &str); 4] = [
        (p.scale, &mut p.scale_v, "ScaleV", "Scale"),
        (p.z_scale, &mut p.z_scale_v, "ZScaleV", "ZScale"),
        (p.trunk_scale, &mut p.trunk_scale_v, "0ScaleV", "0Scale"),
        (
            p.level[0].length,
            &mut p.level[0].length_v,
            "0LengthV",
            "0Length",
        ),
    ];
    for (base, v, v_name, base_name) in pairs {
        if *v > base {
            notes.push(format!(
                "{v_name} {v} exceeds {base_name} {base} and could make a negative size; clamped to {base}"
            ));
            *v = base;
        }
    }
    p.notes.extend(notes);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_names_values_and_defaults() {
        let xml = r#"<?xml version='1.0' ?>
<arbaro><species name='tiny'>
  <!-- comment -->
  <param name='Shape' value='7'/>
  <param name="1DownAngle" value="60.0"/>
  <param name='LeafShape' value='disc3'/>
</species></arbaro>"#;
        let p = from_arbaro_xml(xml, "tiny.xml").unwrap();
        assert_eq!(p.name, "tiny");
        assert_eq!(p.shape, 7);
        assert_eq!(p.level[1].down_angle, 60.0);
        assert_eq!(p.leaf_shape, 0);
        assert_eq!(
            p.level[2].branches, 5,
            "missing parameters take Arbaro's defaults"
        );
    }

    #[test]
    fn unknown_parameter_is_named_with_its_line() {
        let xml =
            "<arbaro><species name='x'>\n<param name='Wobble' value='1'/>\n</species></arbaro>";
        let err = from_arbaro_xml(xml, "w.xml").unwrap_err().to_string();
        assert!(
            err.contains("Wobble") && err.contains("w.xml, line 2"),
            "{err}"
        );
    }

    #[test]
    fn malformed_xml_is_an_error() {
        for xml in [
            "<arbaro><species name='x'><param name='Shape' value='1'></arbaro>",
            "<arbaro><species name='x'><param name='Shape' value='round'/></species></arbaro>",
            "<arbaro></arbaro>",
            "not xml at all <",
        ] {
            assert!(from_arbaro_xml(xml, "m.xml").is_err(), "{xml}");
        }
    }

    #[test]
    fn oversized_variation_is_clamped_with_a_note() {
        let xml = "<arbaro><species name='grass'><param name='Scale' value='0.5'/>\
                   <param name='ScaleV' value='0.7'/></species></arbaro>";
        let p = from_arbaro_xml(xml, "g.xml").unwrap();
        assert_eq!(p.scale_v, 0.5);
        assert!(p.notes[0].contains("ScaleV 0.7"), "{:?}", p.notes);
        // Sylva's own files stay strict.
        let err = crate::params::from_toml("[params]\nScale = 0.5\nScaleV = 0.7\n", "g.toml")
            .unwrap_err();
        assert!(err.to_string().contains("ScaleV"), "{err}");
    }
}
