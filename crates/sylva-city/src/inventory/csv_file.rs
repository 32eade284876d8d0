//! A CSV inventory: a header line, then a row per tree.

use super::{MAX_ROWS, Record, Records, Rejected};
use crate::error::CityError;
use std::path::Path;

/// Reads every row of the CSV file at `path`. A line the CSV reader cannot read (broken
/// quotes, text that is not UTF-8) is rejected and the rest read on.
pub fn read(path: &Path) -> Result<Records, CityError> {
    let file = std::fs::File::open(path).map_err(|e| CityError::inventory(path, e.to_string()))?;
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(std::io::BufReader::new(file));
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| CityError::inventory(path, format!("the header line cannot be read: {e}")))?
        .iter()
        .map(|h| h.trim_start_matches('\u{feff}').to_string())
        .collect();
    if header.iter().all(|h| h.is_empty()) {
        return Err(CityError::inventory(
            path,
            "the file is empty or has no header line",
        ));
    }
    let mut out = Records {
        header: header.clone(),
        ..Default::default()
    };
    let mut record = csv::StringRecord::new();
    loop {
        let line = reader.position().line() as usize;
        match reader.read_record(&mut record) {
            Ok(false) => break,
            Ok(true) => {
                if out.rows.len() >= MAX_ROWS {
                    return Err(CityError::inventory(
                        path,
                        format!("more than {MAX_ROWS} rows; split the inventory"),
                    ));
                }
                out.rows.push(Record {
                    line: record.position().map_or(line, |p| p.line() as usize),
                    fields: header
                        .iter()
                        .zip(record.iter())
                        .map(|(h, v)| (h.clone(), v.to_string()))
                        .collect(),
                    point: None,
                });
            }
            Err(e) => {
                let line = e.position().map_or(line, |p| p.line() as usize);
                if matches!(e.kind(), csv::ErrorKind::Io(_)) {
                    return Err(CityError::inventory(path, format!("line {line}: {e}")));
                }
                out.rejected.push(Rejected {
                    line,
                    reason: format!("the line cannot be read as CSV: {e}"),
                });
            }
        }
    }
    Ok(out)
}
