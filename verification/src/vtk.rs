//! The shell's surface over time as VTK files (issue 15): one `.vtu` (XML unstructured
//! grid, written by the `vtkio` crate) per frame of a run's history and a `.pvd` series
//! that ParaView opens as one time-dependent data set.
//!
//! **Grid**: the points are the frame's grid σ_i × ζ_j (the mesh's nodes), point
//! (i, j) at index i·n_ζ + j with the mid-surface position r(σ_i, ζ_j) (m); the cells are
//! the quads (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1) — i + 1 taken modulo n_σ, so
//! the loop is closed. **Point data**: `displacement` (3 components, m) = r − (g(σ) +
//! ζ e_z), the deflection from the undeformed placement on the contour (ν n_g + (z − ζ)
//! e_z); `membrane_force` n_σσ (N/m), `bending_moment` m_σσ (N), `contact_pressure` Pγ
//! (N/m²), `interlayer_shear` |u| (m) — each present in the frame. `vtkio` writes the arrays as `format="binary"`:
//! base64 of a little-endian UInt64 byte count followed by the little-endian values, not
//! compressed (no compression back-end: pure Rust).

use std::path::{Path, PathBuf};

use drive::contour::Contour;
use drive::result::{SurfaceFields, TimeSeries};
use vtkio::model::{Attribute, Attributes, ByteOrder, CellType, Cells, DataArray, DataSet, ElementType, IOBuffer, UnstructuredGridPiece, Version, VertexNumbers, Vtk};

/// The scalar point fields written besides the displacement, when present in a frame.
pub const SCALARS: [&str; 4] = ["membrane_force", "bending_moment", "contact_pressure", "interlayer_shear"];

/// Why VTK output was not written.
#[derive(Debug, thiserror::Error)]
pub enum VtkError {
    /// The output path exists and is no directory.
    #[error("--vtk {}: exists and is not a directory", .0.display())]
    NotADirectory(PathBuf),
    /// The directory cannot be created.
    #[error("--vtk {}: cannot create the directory: {message}", .dir.display())]
    CreateDirectory {
        /// The directory.
        dir: PathBuf,
        /// The system's message.
        message: String,
    },
    /// The run has no frames of surface fields (not a shell run).
    #[error("the run has no frames of surface fields to write as VTK (a shell run writes them)")]
    NoFrames,
    /// A frame lacks the position fields.
    #[error("frame {frame} lacks the surface field `{field}`")]
    MissingField {
        /// Frame index.
        frame: usize,
        /// Field name.
        field: &'static str,
    },
    /// vtkio failed to write a file.
    #[error("writing {}: {message}", .file.display())]
    Write {
        /// The file.
        file: PathBuf,
        /// vtkio's message.
        message: String,
    },
    /// The series file failed.
    #[error(transparent)]
    Series(#[from] crate::files::WriteError),
}

/// What was written.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// The `.vtu` files, in time order, with their times (s).
    pub frames: Vec<(PathBuf, f64)>,
    /// The `.pvd` series.
    pub series: PathBuf,
}

/// Refuses an output path that exists and is not a directory (checked before a solve).
///
/// # Errors
/// [`VtkError::NotADirectory`].
pub fn check_directory(dir: &Path) -> Result<(), VtkError> {
    if dir.exists() && !dir.is_dir() {
        return Err(VtkError::NotADirectory(dir.to_path_buf()));
    }
    Ok(())
}

/// The grid's points (x, y, z per point) and the displacement from the undeformed
/// placement g(σ) + ζ e_z.
fn points(frame: &SurfaceFields, contour: &Contour, k: usize) -> Result<(Vec<f64>, Vec<f64>), VtkError> {
    let field = |name: &'static str| frame.values.get(name).ok_or(VtkError::MissingField { frame: k, field: name });
    let (x, y, z) = (field("x")?, field("y")?, field("z")?);
    let n = frame.sigma.len() * frame.zeta.len();
    let (mut p, mut d) = (Vec::with_capacity(3 * n), Vec::with_capacity(3 * n));
    for (i, &s) in frame.sigma.iter().enumerate() {
        let g = contour.position(s, 0.0);
        for (j, &q) in frame.zeta.iter().enumerate() {
            let r = [x[i][j], y[i][j], z[i][j]];
            p.extend(r);
            d.extend([r[0] - g[0], r[1] - g[1], r[2] - q]);
        }
    }
    Ok((p, d))
}

/// The closed quad mesh of an n_σ × n_ζ grid: (connectivity, offsets).
fn quads(n_sigma: usize, n_zeta: usize) -> (Vec<u64>, Vec<u64>) {
    let mut connectivity = Vec::with_capacity(4 * n_sigma * n_zeta);
    let mut offsets = Vec::new();
    let id = |i: usize, j: usize| ((i % n_sigma) * n_zeta + j) as u64;
    for i in 0..n_sigma {
        for j in 0..n_zeta.saturating_sub(1) {
            connectivity.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            offsets.push(connectivity.len() as u64);
        }
    }
    (connectivity, offsets)
}

/// The VTK model of one frame.
fn model(frame: &SurfaceFields, contour: &Contour, k: usize) -> Result<Vtk, VtkError> {
    let (p, d) = points(frame, contour, k)?;
    let (connectivity, offsets) = quads(frame.sigma.len(), frame.zeta.len());
    let cells = offsets.len();
    let mut point = vec![Attribute::DataArray(DataArray { name: "displacement".into(), elem: ElementType::Vectors, data: IOBuffer::F64(d) })];
    for name in SCALARS {
        if let Some(rows) = frame.values.get(name) {
            let values: Vec<f64> = rows.iter().flatten().copied().collect();
            point.push(Attribute::DataArray(DataArray { name: name.into(), elem: ElementType::Scalars { num_comp: 1, lookup_table: None }, data: IOBuffer::F64(values) }));
        }
    }
    Ok(Vtk {
        version: Version::new(),
        byte_order: ByteOrder::LittleEndian,
        title: String::new(),
        file_path: None,
        data: DataSet::inline(UnstructuredGridPiece {
            points: IOBuffer::F64(p),
            cells: Cells { cell_verts: VertexNumbers::XML { connectivity, offsets }, types: vec![CellType::Quad; cells] },
            data: Attributes { point, cell: vec![] },
        }),
    })
}

/// Writes every frame of `history` with surface fields as `<name>_NNNN.vtu` into `dir`
/// (created if absent) and the series `<name>.pvd` (module documentation).
///
/// # Errors
/// [`VtkError`] naming the file or the missing field; nothing of a failed file is left
/// as a series entry (the series is written last).
pub fn write_series(dir: &Path, name: &str, contour: &Contour, history: &TimeSeries) -> Result<Written, VtkError> {
    check_directory(dir)?;
    let frames: Vec<(f64, &SurfaceFields)> = history.frames.iter().filter_map(|f| f.surface.as_ref().map(|s| (f.time, s))).collect();
    if frames.is_empty() {
        return Err(VtkError::NoFrames);
    }
    std::fs::create_dir_all(dir).map_err(|e| VtkError::CreateDirectory { dir: dir.to_path_buf(), message: e.to_string() })?;
    let mut written = Vec::new();
    for (k, (time, frame)) in frames.into_iter().enumerate() {
        let file = dir.join(format!("{name}_{k:04}.vtu"));
        let mut xml = Vec::new();
        model(frame, contour, k)?.write_xml(&mut xml).map_err(|e| VtkError::Write { file: file.clone(), message: e.to_string() })?;
        let text = String::from_utf8(xml).map_err(|e| VtkError::Write { file: file.clone(), message: e.to_string() })?;
        // through the project's writer: never half a file, never over a link or directory
        crate::files::write_file(&file, &text)?;
        written.push((file, time));
    }
    let mut pvd = String::from("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n");
    for (file, time) in &written {
        let base = file.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
        pvd.push_str(&format!("    <DataSet timestep=\"{time:e}\" group=\"\" part=\"0\" file=\"{base}\"/>\n"));
    }
    pvd.push_str("  </Collection>\n</VTKFile>\n");
    let series = dir.join(format!("{name}.pvd"));
    crate::files::write_file(&series, &pvd)?;
    Ok(Written { frames: written, series })
}
