//! A point solve's fields as Parquet, in long format: columns X, Y (Hertzian units, x/b and y/b),
//! P (p/p_h) and H (Moes units), one row per node of the finest grid in the solver's order (X
//! fastest: row j * nx + i holds node (X_i, Y_j)), zstd-compressed, with the case and the ehlmap
//! version in the footer key-value metadata. A non-finite value is stored as null.

use crate::solve::point::PointFields;
use crate::store::error::StoreError;
use crate::store::table::{write_table, Column};
use std::path::Path;

/// Write `fields` to `path` (created or replaced) with `meta` as footer key-value pairs (`nx`
/// and `ny`, the nodes per direction, are added). Fails when `p` or `h` do not hold
/// `x.len() * y.len()` values.
pub fn write_fields(
    path: &Path,
    fields: &PointFields,
    meta: &[(&str, String)],
) -> Result<(), StoreError> {
    let (nx, ny) = (fields.x.len(), fields.y.len());
    let n = nx * ny;
    if fields.p.len() != n || fields.h.len() != n {
        return Err(StoreError::FieldsShape {
            nx,
            ny,
            p: fields.p.len(),
            h: fields.h.len(),
        });
    }
    let mut x = Vec::with_capacity(n);
    let mut y = Vec::with_capacity(n);
    for &yj in &fields.y {
        x.extend_from_slice(&fields.x);
        y.extend(std::iter::repeat_n(yj, nx));
    }
    let cols = vec![
        Column::F64("X", x),
        Column::F64("Y", y),
        Column::F64("P", fields.p.clone()),
        Column::F64("H", fields.h.clone()),
    ];
    let mut kv: Vec<(&str, String)> = meta.to_vec();
    kv.push(("nx", nx.to_string()));
    kv.push(("ny", ny.to_string()));
    write_table(path, cols, &kv)
}

#[cfg(test)]
mod tests {
    use super::*;
    use arrow_array::Float64Array;
    use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;

    #[test]
    fn fields_round_trip() {
        let (nx, ny) = (5, 3);
        let x: Vec<f64> = (0..nx).map(|i| -2.0 + i as f64).collect();
        let y: Vec<f64> = (0..ny).map(|j| -1.0 + j as f64).collect();
        let mut p = vec![];
        let mut h = vec![];
        for &yj in &y {
            for &xi in &x {
                p.push((1.0 - xi * xi / 4.0 - yj * yj).max(0.0));
                h.push(0.5 + xi * xi / 2.0 + yj * yj / 2.0);
            }
        }
        h[7] = f64::NAN;
        let f = PointFields {
            x,
            y,
            p,
            h,
            p_asperity: None,
        };
        let dir = std::env::temp_dir().join(format!("ehlmap-fields-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("fields.parquet");
        write_fields(
            &path,
            &f,
            &[("contact", "point".into()), ("D", "0.5".into())],
        )
        .unwrap();

        let builder =
            ParquetRecordBatchReaderBuilder::try_new(std::fs::File::open(&path).unwrap()).unwrap();
        let kv = builder
            .metadata()
            .file_metadata()
            .key_value_metadata()
            .unwrap()
            .clone();
        let get = |k: &str| kv.iter().find(|e| e.key == k).and_then(|e| e.value.clone());
        assert_eq!(get("D").as_deref(), Some("0.5"));
        assert_eq!(get("nx").as_deref(), Some("5"));
        assert_eq!(get("ny").as_deref(), Some("3"));
        assert!(get("ehlmap_version").is_some());
        let mut cols: [Vec<Option<f64>>; 4] = Default::default();
        for b in builder.build().unwrap() {
            let b = b.unwrap();
            for (c, name) in cols.iter_mut().zip(["X", "Y", "P", "H"]) {
                let a = b.column_by_name(name).unwrap();
                let a = a.as_any().downcast_ref::<Float64Array>().unwrap();
                c.extend(a.iter());
            }
        }
        assert_eq!(cols[0].len(), nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let r = j * nx + i;
                assert_eq!(cols[0][r], Some(f.x[i]));
                assert_eq!(cols[1][r], Some(f.y[j]));
                assert_eq!(cols[2][r], Some(f.p[r]));
                let want = f.h[r].is_finite().then_some(f.h[r]);
                assert_eq!(cols[3][r], want, "row {r}");
            }
        }
        let bad = PointFields {
            p: vec![0.0; 2],
            ..f.clone()
        };
        assert!(write_fields(&dir.join("bad.parquet"), &bad, &[]).is_err());
        std::fs::remove_dir_all(&dir).ok();
    }
}
