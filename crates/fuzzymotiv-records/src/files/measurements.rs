//! A calibration's measurements file (`fuzzymotiv calibrate`): CSV rows `sensor,
//! distance_mm, reading` (comments `#`, spaces trimmed) read into
//! [`fuzzymotiv::simulation::Measurement`]s; a missing column or a value that is not a number
//! names the file, the row and the column.

use std::path::Path;

use fuzzymotiv::experiment::SetupError;
use fuzzymotiv::params::FieldError;
use fuzzymotiv::simulation::Measurement;

use crate::files::bounded::{InputKind, csv_refusal, open_input};
use crate::files::error::CliError;

/// A field's error as the setup's (exit 2, naming the file and the field).
pub fn field_error(e: FieldError) -> CliError {
    CliError::Setup(SetupError::Field(e))
}

/// One CSV row as written.
#[derive(serde::Deserialize)]
struct Row {
    sensor: usize,
    distance_mm: f64,
    reading: f64,
}

/// Reads the measurements; a missing column or a value that is not a number names the file,
/// the row and the column.
pub fn read_measurements(path: &Path) -> Result<Vec<Measurement>, CliError> {
    let source = path.display().to_string();
    let input = open_input(path, InputKind::table("measurements file"))?;
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(input);
    let headers = reader
        .headers()
        .map_err(|e| {
            csv_refusal(&e)
                .unwrap_or_else(|| CliError::input(format!("{source}: not a CSV file: {e}")))
        })?
        .clone();
    for column in ["sensor", "distance_mm", "reading"] {
        if !headers.iter().any(|h| h == column) {
            let reason = format!(
                "the header has no column `{column}` (it needs sensor, distance_mm and reading; found {})",
                headers.iter().collect::<Vec<_>>().join(", ")
            );
            return Err(field_error(
                FieldError::new(column, reason).in_source(&source),
            ));
        }
    }
    let mut rows = Vec::new();
    for (i, record) in reader.deserialize::<Row>().enumerate() {
        let row = record.map_err(|e| {
            if let Some(refused) = csv_refusal(&e) {
                return refused;
            }
            let column = e
                .position()
                .and(match e.kind() {
                    csv::ErrorKind::Deserialize { err, .. } => err.field(),
                    _ => None,
                })
                .and_then(|k| headers.get(k as usize))
                .unwrap_or("(row)")
                .to_string();
            let reason = format!("data row {}: {e}; sensor is a whole number 0–7, distance_mm and reading are numbers", i + 1);
            field_error(FieldError::new(column, reason).in_source(&source))
        })?;
        rows.push(Measurement {
            sensor: row.sensor,
            distance_mm: row.distance_mm,
            reading: row.reading,
        });
    }
    if rows.is_empty() {
        return Err(CliError::input(format!(
            "{source}: holds no measurements (a header and no rows)"
        )));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Vec<Measurement>, CliError> {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bench.csv");
        std::fs::write(&path, text).unwrap();
        read_measurements(&path)
    }

    /// Rows are read with comments and spaces left out; a file without a column, with a
    /// value that is not a number, or without rows is refused, naming what is wrong.
    #[test]
    fn measurements_are_read_and_bad_ones_refused_naming_the_column() {
        let rows =
            read("# bench\nsensor, distance_mm, reading\n2, 10, 900\n2, 20.5, 400\n").unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(
            (rows[1].sensor, rows[1].distance_mm, rows[1].reading),
            (2, 20.5, 400.0)
        );
        let e = read("sensor,distance_mm\n1,10\n").unwrap_err().to_string();
        assert!(e.contains("reading") && e.contains("bench.csv"), "{e}");
        let e = read("sensor,distance_mm,reading\n1,ten,5\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("distance_mm") && e.contains("data row 1"), "{e}");
        let e = read("sensor,distance_mm,reading\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("holds no measurements"), "{e}");
    }
}
