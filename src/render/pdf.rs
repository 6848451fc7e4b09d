//! PDF figures: the SVG drawing of [`crate::render::plot`] read into a render tree (usvg) and
//! written as one PDF page (svg2pdf) of the figure's physical size. The embedded DejaVu Sans is
//! the only font known to the conversion (no system fonts are read), embedded as a subset; the
//! labels stay text (selectable, searchable, found by a PDF reader's text extraction), the
//! curves stay vectors, and the heat maps of fine grids stay the SVG's raster images.

use std::sync::{Arc, OnceLock};

use crate::error::{Error, Result};
use crate::figure::Figure;
use crate::render::plot::{Print, svg_string_at};

/// The font database of the conversion: DejaVu Sans regular and bold, nothing else.
fn fonts() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    Arc::clone(DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(dejavu::sans::regular().to_vec());
        db.load_font_data(dejavu::sans::bold().to_vec());
        db.set_sans_serif_family("DejaVu Sans");
        Arc::new(db)
    }))
}

/// The figure as a PDF document in memory, `print.width_of(fig)` mm wide.
///
/// # Errors
/// [`Error::Render`] when drawing or converting fails.
pub fn pdf_bytes_at(fig: &Figure, print: &Print) -> Result<Vec<u8>> {
    from_svg(&svg_string_at(fig, print)?)
}

/// A PDF page from an SVG document of the renderer (its size from the root's `width` and
/// `height`, text in DejaVu Sans).
///
/// # Errors
/// [`Error::Render`] when the SVG cannot be read or the PDF not written.
pub fn from_svg(svg: &str) -> Result<Vec<u8>> {
    let render_error = |message: String| Error::Render {
        format: "pdf",
        message,
    };
    let options = usvg::Options {
        font_family: "DejaVu Sans".into(),
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| render_error(e.to_string()))?;
    // usvg gives sizes in CSS pixels (96 per inch): the page keeps the figure's width in mm.
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions { dpi: 96.0 },
    )
    .map_err(|e| render_error(e.to_string()))
}
