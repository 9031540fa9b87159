//! Double-buffered bands: band k+1 is drawn into one buffer while band k,
//! in the other, is still being sent to the display (by DMA, or by an
//! interrupt-driven SPI driver).
//!
//! With one band buffer ([`TreeRenderer::try_render_banded_in`]) the CPU
//! waits for every band to reach the display before it may draw the next
//! into the same memory. With two, the transfer of a band and the drawing
//! of the next overlap, so a frame costs about `max(draw, send)` instead
//! of `draw + send`, for one more band buffer of RAM.
//!
//! # Contract between the loop and the driver ([`BandTransfer`])
//!
//! [`TreeRenderer::render_double_buffered_in`] draws the bands top to
//! bottom, alternately into [`BandBuffers::front`] and
//! [`BandBuffers::back`], and calls the driver like this (band `k` at row
//! `y_k`):
//!
//! ```text
//! draw 0 → start(y0, band 0)
//! draw 1 → finish() → start(y1, band 1)        (band 0's buffer is back)
//! draw 2 → finish() → start(y2, band 2)        (band 2 reuses band 0's buffer)
//! ...
//! draw n−1 → finish() → start(y_{n−1}, band n−1) → finish()
//! ```
//!
//! * **One transfer at a time.** `start` is called only when no transfer
//!   is in flight; `finish` is called exactly once after each successful
//!   `start`, before the next `start` and before the call returns.
//! * **The driver owns a band while it is sent.** `start` receives the
//!   band by value ([`Framebuffer`], the `&'b mut` storage inside it), so
//!   nothing else can touch those pixels until the driver gives them back
//!   from `finish`. A DMA driver keeps the framebuffer in itself, points
//!   its DMA stream at [`Framebuffer::data`] (or
//!   [`Framebuffer::panel_bytes`]) and returns from `start` at once;
//!   `finish` waits for transfer-complete and returns the framebuffer. With
//!   `'static` buffers (e.g. from `static_cell`) that hold is sound even if
//!   the driver is leaked mid-transfer.
//! * **The storage comes back.** `finish` must return the framebuffer its
//!   `start` received (the loop draws a later band into its storage; any
//!   other framebuffer of at least a band's size works, a smaller one ends
//!   the frame with a [`RenderError::Band`]).
//! * **Errors stop the frame.** The first error of `start` or `finish`
//!   ends the frame: no later band is drawn or started, a transfer in
//!   flight is still finished (its error, if any, is dropped in favour of
//!   the first), and the first error comes back as
//!   [`BandError::Display`].
//! * **The same pixels.** The bands are exactly those of
//!   [`TreeRenderer::try_render_banded_in`] with one buffer (and so of a
//!   full-frame render): only which buffer holds a band changes.

use super::cached::{bands_into, BandStore};
use super::{check_capacities, BandError, Frame, RenderError, TreeRenderer};
use crate::effects::Compiled;
use crate::raster::{Framebuffer, FramebufferError, PixelFormat, Precision, RenderStats};
use crate::reader::Tree;

/// A display link that sends one band while the next is drawn (see the
/// module docs for the order of the calls).
///
/// A driver that sends synchronously (blocking SPI) implements it by
/// sending in `start` and returning the band from `finish`; it then gains
/// nothing over one buffer, but the same firmware runs with either.
///
/// ```
/// use fpt_nostd::raster::{Framebuffer, Rgb565BeFormat};
/// use fpt_nostd::render::BandTransfer;
///
/// /// A stand-in for a DMA SPI driver: `start` would write the panel's
/// /// window (CASET/RASET/RAMWR) and start the DMA stream from the band's
/// /// bytes; here it only keeps the band, and `finish` "sends" it.
/// struct Dma<'b> {
///     in_flight: Option<(i32, Framebuffer<'b, Rgb565BeFormat>)>,
///     sent: usize,
/// }
///
/// impl<'b> BandTransfer<'b, Rgb565BeFormat> for Dma<'b> {
///     type Error = &'static str;
///     fn start(&mut self, y: i32, band: Framebuffer<'b, Rgb565BeFormat>) -> Result<(), &'static str> {
///         self.in_flight = Some((y, band)); // the DMA reads band.panel_bytes()
///         Ok(())
///     }
///     fn finish(&mut self) -> Result<Framebuffer<'b, Rgb565BeFormat>, &'static str> {
///         // Wait for transfer-complete, then hand the buffer back.
///         let (_y, band) = self.in_flight.take().ok_or("no transfer")?;
///         self.sent += band.panel_bytes().len();
///         Ok(band)
///     }
/// }
/// # let _ = Dma { in_flight: None, sent: 0 };
/// ```
pub trait BandTransfer<'b, F: PixelFormat> {
    /// The driver's error.
    type Error;
    /// Starts sending `band`, frame rows `y .. y + band.height()`, and
    /// keeps it until [`BandTransfer::finish`]. Called only when no
    /// transfer is in flight.
    fn start(&mut self, y: i32, band: Framebuffer<'b, F>) -> Result<(), Self::Error>;
    /// Waits until the transfer started last is complete and gives its
    /// band back.
    fn finish(&mut self) -> Result<Framebuffer<'b, F>, Self::Error>;
}

/// The two band buffers of
/// [`TreeRenderer::render_double_buffered_in`]: storage for `rows`
/// full-width rows each, and the colour every band starts from.
#[derive(Debug)]
pub struct BandBuffers<'b, F: PixelFormat> {
    /// At least `rows × words_per_row(width)` words: bands 0, 2, 4, …
    pub front: &'b mut [F::Word],
    /// As large as `front`: bands 1, 3, 5, …
    pub back: &'b mut [F::Word],
    /// Rows per band (at least 1).
    pub rows: u32,
    /// Background colour.
    pub background: F::Color,
}

/// The loop's side of the contract: hands the buffers out in turns and
/// keeps at most one transfer in flight.
struct Double<'b, 'l, F: PixelFormat, T: BandTransfer<'b, F>> {
    free: [Option<&'b mut [F::Word]>; 2],
    busy: bool,
    link: &'l mut T,
    error: Option<T::Error>,
}

impl<'b, F: PixelFormat, T: BandTransfer<'b, F>> Double<'b, '_, F, T> {
    /// Waits for the transfer in flight; its buffer, or `None` after an
    /// error (kept if it is the first).
    fn wait(&mut self) -> Option<&'b mut [F::Word]> {
        self.busy = false;
        match self.link.finish() {
            Ok(fb) => Some(fb.into_storage()),
            Err(e) => {
                self.error.get_or_insert(e);
                None
            }
        }
    }

    /// Puts a buffer back among the free ones.
    fn put(&mut self, buf: &'b mut [F::Word]) {
        if let Some(slot) = self.free.iter_mut().find(|s| s.is_none()) {
            *slot = Some(buf);
        }
    }
}

impl<'b, F: PixelFormat, T: BandTransfer<'b, F>> BandStore<'b, F> for Double<'b, '_, F, T> {
    fn take(&mut self) -> Option<&'b mut [F::Word]> {
        if let Some(buf) = self.free.iter_mut().find_map(Option::take) {
            return Some(buf);
        }
        // Both buffers out (not reached: `emit` gets one back before it
        // starts a transfer): wait for the one in flight.
        if self.busy {
            self.wait()
        } else {
            None
        }
    }

    fn emit(&mut self, y: i32, fb: Framebuffer<'b, F>) -> bool {
        if self.busy {
            // The band before this one was sent while this one was drawn.
            let Some(done) = self.wait() else {
                // This band was not started: its buffer stays ours.
                self.put(fb.into_storage());
                return false;
            };
            self.put(done);
        }
        match self.link.start(y, fb) {
            Ok(()) => {
                self.busy = true;
                true
            }
            Err(e) => {
                self.error.get_or_insert(e);
                false
            }
        }
    }
}

impl<P: Precision, const V: usize, E: Compiled> TreeRenderer<P, V, E> {
    /// [`TreeRenderer::try_render_banded_in`] with two band buffers: band
    /// k+1 is drawn while `link` sends band k (the contract is in the
    /// module docs of `render::double`, summarised here). `link.start`
    /// gets each finished band by value and `link.finish` waits for it to
    /// be sent and gives it back; at most one transfer is in flight, and
    /// none when this returns. The first error of either ends the frame
    /// and comes back as [`BandError::Display`]. The bands' pixels are
    /// those of one buffer, bit for bit.
    ///
    /// Both buffers are checked before anything is drawn or sent: each
    /// must hold `rows` full rows, else [`RenderError::Band`]. They are
    /// lent to the loop and the link for the frame and are back in
    /// `bands` when this returns (in either field: which one holds which
    /// changes), so that `'static` buffers serve frame after frame; the
    /// band of a `start` or `finish` that failed stays with the driver and
    /// its field is left empty (the next frame is then refused as too
    /// small).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb565;
    /// use fpt_nostd::raster::{FloatLibm, Framebuffer, Libm, Orbit, Rgb565BeFormat};
    /// use fpt_nostd::reader::Tree;
    /// use fpt_nostd::render::{BandBuffers, BandTransfer, Frame, TreeRenderer};
    ///
    /// /// Keeps the band in flight, as a DMA driver would.
    /// struct Link<'b> {
    ///     in_flight: Option<Framebuffer<'b, Rgb565BeFormat>>,
    ///     rows: Vec<i32>,
    /// }
    /// impl<'b> BandTransfer<'b, Rgb565BeFormat> for Link<'b> {
    ///     type Error = ();
    ///     fn start(&mut self, y: i32, band: Framebuffer<'b, Rgb565BeFormat>) -> Result<(), ()> {
    ///         assert!(self.in_flight.is_none()); // one transfer at a time
    ///         self.rows.push(y);
    ///         self.in_flight = Some(band);
    ///         Ok(())
    ///     }
    ///     fn finish(&mut self) -> Result<Framebuffer<'b, Rgb565BeFormat>, ()> {
    ///         self.in_flight.take().ok_or(())
    ///     }
    /// }
    ///
    /// let tree = Tree::from_bytes(include_bytes!("../../../firmware/trees/vise.fpt")).unwrap();
    /// let mut r = TreeRenderer::<FloatLibm<4>, 64>::new(64, 64).unwrap();
    /// let orbit = Orbit::framing::<Libm>(tree.bounding_radius(), 0.5, 0.4, 1.0, 1.0);
    /// let frame = Frame::relative(&tree, &orbit.camera::<Libm>(1.0));
    /// let (mut a, mut b) = ([0u16; 64 * 16], [0u16; 64 * 16]);
    /// let mut bands = BandBuffers::<Rgb565BeFormat> {
    ///     front: &mut a,
    ///     back: &mut b,
    ///     rows: 16,
    ///     background: Rgb565::new(0, 0, 0),
    /// };
    /// let mut link = Link { in_flight: None, rows: Vec::new() };
    /// r.render_double_buffered_in::<64, _, _>(&tree, &frame, &mut bands, &mut [], &mut link)
    ///     .unwrap();
    /// assert_eq!(link.rows, [0, 16, 32, 48]);
    /// assert!(link.in_flight.is_none()); // the last band was finished
    /// // Both buffers are back for the next frame.
    /// assert_eq!((bands.front.len(), bands.back.len()), (64 * 16, 64 * 16));
    /// ```
    pub fn render_double_buffered_in<'b, const N: usize, F: PixelFormat, T>(
        &mut self,
        tree: &Tree<'_>,
        frame: &Frame,
        bands: &mut BandBuffers<'b, F>,
        memory: &mut [u32],
        link: &mut T,
    ) -> Result<RenderStats, BandError<T::Error>>
    where
        T: BandTransfer<'b, F>,
    {
        let refuse = |e: RenderError| Err(BandError::Render(e));
        if let Err(e) = check_capacities::<N, V>(tree) {
            return refuse(e.into());
        }
        let view = self.renderer.viewport();
        let rows = bands.rows.clamp(1, view.height().max(1));
        let need = Framebuffer::<F>::required_len(view.width(), rows);
        if bands.front.len() < need || bands.back.len() < need {
            return refuse(RenderError::Band(FramebufferError::BufferTooSmall));
        }
        // Lent to the loop (and the link) for the frame, given back below.
        let front = core::mem::take(&mut bands.front);
        let back = core::mem::take(&mut bands.back);
        let mut store = Double {
            free: [Some(front), Some(back)],
            busy: false,
            link,
            error: None,
        };
        let out = bands_into::<P, E, F, _, N, V>(
            tree,
            frame,
            &mut self.renderer,
            &mut self.scratch,
            (self.ids, memory),
            (rows, bands.background),
            &mut store,
        );
        // Whatever happened, no transfer is left running.
        if store.busy {
            if let Some(buf) = store.wait() {
                store.put(buf);
            }
        }
        let [a, b] = store.free;
        bands.front = a.unwrap_or_default();
        bands.back = b.unwrap_or_default();
        match (store.error, out) {
            (Some(e), _) => Err(BandError::Display(e)),
            (None, Err(e)) => Err(BandError::Render(e)),
            (None, Ok(stats)) => Ok(stats),
        }
    }
}

// The tests draw the firmware's vise, a default file: a compact plane
// table, read with the default feature only.
#[cfg(all(test, feature = "compact-planes"))]
mod tests;
