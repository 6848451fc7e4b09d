//! What a drawn frame leaves for the state: where the parts the mouse can hit were put, the
//! chart's geometry (to turn a cell into a data point), and the first row shown of each
//! scrolled list. [`crate::tui::view::draw`] returns it; the state keeps the last one and reads
//! it when a mouse event arrives. Plain data, so neither side needs the other's code.

use ratatui::crossterm::event::KeyCode;
use ratatui::layout::Rect;

use crate::render::terminal::ChartGeometry;

/// What a click on a [`DrawnLayout::targets`] area means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Show panel `k` of the figure (a panel tab).
    Tab(usize),
    /// Act as this key (an action written in a footer).
    Key(KeyCode),
}

/// Where the last frame put the parts the mouse can hit.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DrawnLayout {
    /// Inside of the scene list.
    pub list: Rect,
    /// First list row shown.
    pub list_offset: usize,
    /// The parameter rows.
    pub form: Rect,
    /// First parameter shown.
    pub form_offset: usize,
    /// The area the chart (axes included) was drawn into.
    pub chart_area: Rect,
    /// The chart's graph, if a chart was drawn.
    pub chart: Option<ChartGeometry>,
    /// The line of panel tabs (empty when the figure has one panel).
    pub tabs: Rect,
    /// The history overlay (its border included).
    pub overlay: Rect,
    /// The history overlay's rows of runs.
    pub history: Rect,
    /// First history entry shown.
    pub history_offset: usize,
    /// The history overlay's footer line (its actions).
    pub history_footer: Rect,
    /// Whether the results were drawn beside (or under) the chart, not as an overlay.
    pub results_beside: bool,
    /// Small areas with a meaning of their own (panel tabs, footer actions), topmost last.
    pub targets: Vec<(Rect, Target)>,
}

impl DrawnLayout {
    /// The topmost target under cell (`column`, `row`).
    pub fn target_at(&self, column: u16, row: u16) -> Option<Target> {
        self.targets
            .iter()
            .rev()
            .find(|(r, _)| hit(*r, column, row))
            .map(|(_, t)| *t)
    }
}

/// Whether cell (`column`, `row`) lies in `r`.
pub fn hit(r: Rect, column: u16, row: u16) -> bool {
    (r.x..r.right()).contains(&column) && (r.y..r.bottom()).contains(&row)
}
