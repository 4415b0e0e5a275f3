//! Parquet written by other tools: a dataset part re-saved with snappy (pyarrow's default),
//! gzip, lz4 or no compression reads back to the same rows, through the dataset reader and
//! `ehlmap fit`; so does one re-saved as pandas and polars do it (integer columns with nulls as
//! floats, large strings). A file of another layout is an error naming the file and the missing
//! column ("not an ehlmap dataset: missing column X"), in the reader, `ehlmap fit` and
//! `ehlmap sweep`. (CI re-saves a part with pyarrow itself: .ci/foreign_parquet.py.)

mod common;
use common::ehlmap;

use arrow_array::{Array, ArrayRef, Float64Array, Int64Array, LargeStringArray, RecordBatch};
use arrow_array::{StringArray, UInt32Array};
use arrow_schema::{DataType, Field, Schema};
use ehlmap::store::results::{part_files, read_dataset};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use parquet::arrow::ArrowWriter;
use parquet::basic::{Compression, GzipLevel};
use parquet::file::properties::WriterProperties;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The committed line dataset (schema 1) and point dataset (schema 2).
fn committed(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// A fresh scratch directory for one test, removed when the test passes.
fn scratch(name: &str) -> common::Scratch {
    common::Scratch::new(&format!("foreign-{name}"))
}

/// The record batches of a Parquet file.
fn batches(path: &Path) -> Vec<RecordBatch> {
    let r = ParquetRecordBatchReaderBuilder::try_new(File::open(path).unwrap())
        .unwrap()
        .build()
        .unwrap();
    r.map(|b| b.unwrap()).collect()
}

/// Write `batches` to `path` with `compression` and no footer metadata (as a notebook would).
fn write(path: &Path, batches: &[RecordBatch], compression: Compression) {
    let props = WriterProperties::builder()
        .set_compression(compression)
        .build();
    let f = File::create(path).unwrap();
    let mut w = ArrowWriter::try_new(f, batches[0].schema(), Some(props)).unwrap();
    for b in batches {
        w.write(b).unwrap();
    }
    w.close().unwrap();
}

/// The only part of a committed dataset.
fn only_part(name: &str) -> PathBuf {
    let parts = part_files(&committed(name)).unwrap();
    assert_eq!(parts.len(), 1);
    parts[0].clone()
}

#[test]
fn parts_resaved_with_other_codecs_read_to_the_same_rows() {
    let dir = scratch("codecs");
    for name in ["smoke-line", "point-257"] {
        let want = read_dataset(&committed(name)).unwrap();
        let b = batches(&only_part(name));
        for (tag, codec) in [
            ("snappy", Compression::SNAPPY),
            ("gzip", Compression::GZIP(GzipLevel::default())),
            ("lz4raw", Compression::LZ4_RAW),
            ("lz4", Compression::LZ4),
            ("none", Compression::UNCOMPRESSED),
        ] {
            let ds = dir.join(format!("{name}-{tag}"));
            std::fs::create_dir_all(&ds).unwrap();
            // A name a notebook might choose: every visible *.parquet of the directory is read.
            write(&ds.join(format!("resaved-{tag}.parquet")), &b, codec);
            assert_eq!(read_dataset(&ds).unwrap(), want, "{name} {tag}");
        }
    }
}

#[test]
fn ehlmap_fit_reads_a_snappy_dataset_and_file() {
    let dir = scratch("fit");
    let ds = dir.join("smoke-snappy");
    std::fs::create_dir_all(&ds).unwrap();
    let file = ds.join("part-1of1-0001.parquet");
    write(
        &file,
        &batches(&only_part("smoke-line")),
        Compression::SNAPPY,
    );
    for (input, out) in [
        (&ds, dir.join("report-dir")),
        (&file, dir.join("report-file")),
    ] {
        let o = ehlmap(&[
            "fit",
            input.to_str().unwrap(),
            "--no-limit-solves",
            "--json",
            "--out",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(0), "{err}");
        let fit: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert!(fit["line"]["h_c"]["params"].is_array(), "{fit}");
        assert!(out.join("report.md").exists());
    }
}

/// `b` with every column passed through `f` (name, array) -> (field, array).
fn map_columns(
    b: &RecordBatch,
    f: impl Fn(&str, &ArrayRef) -> Option<(DataType, ArrayRef)>,
) -> RecordBatch {
    let mut fields = vec![];
    let mut cols = vec![];
    for (field, col) in b.schema().fields().iter().zip(b.columns()) {
        match f(field.name(), col) {
            Some((t, a)) => {
                fields.push(Field::new(field.name(), t, true));
                cols.push(a);
            }
            None => {
                fields.push(field.as_ref().clone());
                cols.push(col.clone());
            }
        }
    }
    RecordBatch::try_new(Arc::new(Schema::new(fields)), cols).unwrap()
}

#[test]
fn pandas_and_polars_types_read() {
    let dir = scratch("types");
    let name = "point-257";
    let want = read_dataset(&committed(name)).unwrap();
    let mut b = batches(&only_part(name));
    assert_eq!(b.len(), 1);
    let b = b.remove(0);
    // pandas: an integer column with nulls becomes float64; polars: strings are large strings;
    // an unsigned count where a signed one is stored.
    let resaved = map_columns(&b, |n, a| {
        if let Some(i) = a.as_any().downcast_ref::<Int64Array>() {
            if n == "max_cycles" {
                let u: UInt32Array = i.iter().map(|v| v.map(|v| v as u32)).collect();
                return Some((DataType::UInt32, Arc::new(u)));
            }
            let f: Float64Array = i.iter().map(|v| v.map(|v| v as f64)).collect();
            return Some((DataType::Float64, Arc::new(f)));
        }
        if let Some(s) = a.as_any().downcast_ref::<StringArray>() {
            let l: LargeStringArray = s.iter().collect();
            return Some((DataType::LargeUtf8, Arc::new(l)));
        }
        None
    });
    let ds = dir.join("pandas");
    std::fs::create_dir_all(&ds).unwrap();
    write(
        &ds.join("part-0.parquet"),
        std::slice::from_ref(&resaved),
        Compression::SNAPPY,
    );
    assert_eq!(read_dataset(&ds).unwrap(), want);
    // A float that is not an integer in an integer column is named, with the value.
    let bad = map_columns(&resaved, |n, a| {
        (n == "grid").then(|| {
            let f = a.as_any().downcast_ref::<Float64Array>().unwrap();
            let g: Float64Array = f.iter().map(|v| v.map(|v| v + 0.5)).collect();
            (DataType::Float64, Arc::new(g) as ArrayRef)
        })
    });
    let path = ds.join("part-0.parquet");
    write(&path, &[bad], Compression::SNAPPY);
    let e = read_dataset(&ds).unwrap_err().to_string();
    assert!(
        e.contains(&path.display().to_string())
            && e.contains("`grid`")
            && e.contains("not an integer"),
        "{e}"
    );
    // A null in a required column is named too.
    let null = map_columns(&b, |n, a| {
        (n == "M").then(|| {
            let mut v: Vec<Option<f64>> = (0..a.len()).map(|_| Some(1.0)).collect();
            v[0] = None;
            (
                DataType::Float64,
                Arc::new(Float64Array::from(v)) as ArrayRef,
            )
        })
    });
    write(&path, &[null], Compression::SNAPPY);
    let e = read_dataset(&ds).unwrap_err().to_string();
    assert!(e.contains("column `M`: value \"null\""), "{e}");
}

#[test]
fn a_file_of_another_layout_is_not_an_ehlmap_dataset() {
    let dir = scratch("layout");
    // A table that has nothing to do with ehlmap ...
    let ds = dir.join("other");
    std::fs::create_dir_all(&ds).unwrap();
    let schema = Arc::new(Schema::new(vec![
        Field::new("x", DataType::Float64, false),
        Field::new("label", DataType::Utf8, false),
    ]));
    let b = RecordBatch::try_new(
        schema,
        vec![
            Arc::new(Float64Array::from(vec![1.0, 2.0])),
            Arc::new(StringArray::from(vec!["a", "b"])),
        ],
    )
    .unwrap();
    let other = ds.join("table.parquet");
    write(&other, &[b], Compression::SNAPPY);
    let want = format!(
        "{}: not an ehlmap dataset: missing column `case_id`",
        other.display()
    );
    assert_eq!(read_dataset(&ds).unwrap_err().to_string(), want);
    let o = ehlmap(&["fit", ds.to_str().unwrap(), "--no-limit-solves"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(&want), "{err}");
    // ... and a dataset part without one of its columns.
    let part = only_part("point-257");
    let b = batches(&part);
    let keep: Vec<usize> = (0..b[0].num_columns())
        .filter(|&i| b[0].schema().field(i).name() != "tol_h")
        .collect();
    let cut = b[0].project(&keep).unwrap();
    let ds2 = dir.join("cut");
    std::fs::create_dir_all(&ds2).unwrap();
    let cut_path = ds2.join("part-1of1-0001.parquet");
    write(&cut_path, &[cut], Compression::SNAPPY);
    let e = read_dataset(&ds2).unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "{}: not an ehlmap dataset: missing column `tol_h`",
            cut_path.display()
        )
    );
    // A sweep into a directory holding a foreign file names it and runs nothing.
    let spec = dir.join("other.toml");
    std::fs::write(
        &spec,
        "contact = \"line\"\n[axes]\nM = [5]\nL = [0]\n[numerics]\ngrid = 257\n",
    )
    .unwrap();
    let o = ehlmap(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--progress",
        "none",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(&want), "{err}");
    assert_eq!(part_files(&ds).unwrap(), vec![other]);
}
