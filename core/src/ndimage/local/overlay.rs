//! Samples changed by [`LocalInterpolant::update`](super::LocalInterpolant::update)
//! without writing to the caller's array (which may be read-only, memory
//! mapped, or an array-like not in memory): the changed samples' blocks of
//! the sample grid, copied on first change, read over the source
//! ([`Overlaid`]). Memory: one block per block touched.

use crate::ndimage::NdimageError;
use crate::ndimage::samples::SampleSource;
use crate::scalar::Real;
use std::collections::HashMap;

/// Changed samples, by block of the sample grid.
#[derive(Debug, Clone)]
pub(crate) struct Overlay<T> {
    shape: Vec<usize>,
    edge: Vec<usize>,
    blocks: HashMap<Vec<usize>, Vec<T>>,
}

/// The first and one-past-last index of block `b` of edge `e` on an axis of `n`.
fn span(b: usize, e: usize, n: usize) -> (usize, usize) {
    (b * e, ((b + 1) * e).min(n))
}

impl<T: Real> Overlay<T> {
    /// No changes, blocks of about 256 samples (edge `256^{1/D}`).
    pub(crate) fn new(shape: &[usize]) -> Self {
        let edge = match shape.len() {
            1 => 256,
            2 => 16,
            3 => 8,
            _ => 4,
        };
        Overlay {
            shape: shape.to_vec(),
            edge: shape.iter().map(|&n| edge.min(n).max(1)).collect(),
            blocks: HashMap::new(),
        }
    }

    /// Whether nothing has changed.
    pub(crate) fn is_empty(&self) -> bool {
        self.blocks.is_empty()
    }

    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        self.blocks
            .values()
            .map(|b| b.len() * std::mem::size_of::<T>())
            .sum()
    }

    fn block_box(&self, key: &[usize]) -> (Vec<usize>, Vec<usize>) {
        key.iter()
            .zip(&self.edge)
            .zip(&self.shape)
            .map(|((&b, &e), &n)| span(b, e, n))
            .unzip()
    }

    /// Sets the sample at `idx` (inside the grid) to `value`, its block
    /// read from `base` on its first change; what [`Self::revert`] needs
    /// to undo it is pushed on `undo`.
    fn set<S: SampleSource<T> + ?Sized>(
        &mut self,
        base: &S,
        idx: &[usize],
        value: T,
        undo: &mut Undo<T>,
    ) -> Result<(), NdimageError> {
        let key: Vec<usize> = idx.iter().zip(&self.edge).map(|(i, e)| i / e).collect();
        let (lo, hi) = self.block_box(&key);
        if !self.blocks.contains_key(&key) {
            let mut data = vec![T::zero(); lo.iter().zip(&hi).map(|(l, h)| h - l).product()];
            base.read_box(&lo, &hi, &mut data)?;
            self.blocks.insert(key.clone(), data);
            undo.added.push(key.clone());
        }
        let block = self.blocks.get_mut(&key).expect("inserted");
        let at = idx
            .iter()
            .zip(lo.iter().zip(&hi))
            .fold(0, |s, (&i, (&l, &h))| s * (h - l) + (i - l));
        let old = std::mem::replace(&mut block[at], value);
        undo.old.push((key, at, old));
        Ok(())
    }

    /// Sets the samples `changes` in order (a repeated index keeps the
    /// last value), in place: no copy of the blocks already held. On a
    /// failed read nothing is changed; the [`Undo`] returned takes the
    /// changes back ([`Self::revert`]) where a later step fails.
    pub(crate) fn set_all<'i, S: SampleSource<T> + ?Sized>(
        &mut self,
        base: &S,
        changes: impl Iterator<Item = (&'i [usize], &'i T)>,
    ) -> Result<Undo<T>, NdimageError>
    where
        T: 'i,
    {
        let mut undo = Undo {
            added: Vec::new(),
            old: Vec::new(),
        };
        for (idx, v) in changes {
            if let Err(e) = self.set(base, idx, v.clone(), &mut undo) {
                self.revert(undo);
                return Err(e);
            }
        }
        Ok(undo)
    }

    /// Takes back the changes of one [`Self::set_all`]: the old values in
    /// reverse order (the first change's old value last), then the blocks
    /// it added.
    pub(crate) fn revert(&mut self, undo: Undo<T>) {
        for (key, at, old) in undo.old.into_iter().rev() {
            if let Some(block) = self.blocks.get_mut(&key) {
                block[at] = old;
            }
        }
        for key in undo.added {
            self.blocks.remove(&key);
        }
    }

    /// The boxes of the blocks of `indices` not held yet (what
    /// [`Self::set`] reads).
    pub(crate) fn missing_blocks<'i>(
        &self,
        indices: impl Iterator<Item = &'i [usize]>,
    ) -> Vec<(Vec<usize>, Vec<usize>)> {
        let mut keys: Vec<Vec<usize>> = indices
            .map(|idx| idx.iter().zip(&self.edge).map(|(i, e)| i / e).collect())
            .filter(|k| !self.blocks.contains_key(k))
            .collect();
        keys.sort_unstable();
        keys.dedup();
        keys.iter().map(|k| self.block_box(k)).collect()
    }

    /// Writes the changed samples inside the box `lo..hi` over `out` (the
    /// box's samples in C order).
    pub(crate) fn patch(&self, lo: &[usize], hi: &[usize], out: &mut [T]) {
        if self.blocks.is_empty() {
            return;
        }
        if lo.iter().zip(hi).any(|(l, h)| l >= h) {
            return;
        }
        let dims: Vec<usize> = lo.iter().zip(hi).map(|(l, h)| h - l).collect();
        // The blocks the box overlaps, looked up by key where they are
        // fewer than the blocks held (a long run of updates holds many).
        let first: Vec<usize> = lo.iter().zip(&self.edge).map(|(l, e)| l / e).collect();
        let counts: Vec<usize> = hi
            .iter()
            .zip(&self.edge)
            .zip(&first)
            .map(|((h, e), f)| (h - 1) / e + 1 - f)
            .collect();
        let mut held: Vec<(&Vec<usize>, &Vec<T>)> = Vec::new();
        if counts.iter().product::<usize>() < self.blocks.len() {
            let mut key = vec![0; first.len()];
            super::gather::for_each_index(&counts, |_, idx| {
                for (k, (f, i)) in key.iter_mut().zip(first.iter().zip(idx)) {
                    *k = f + i;
                }
                if let Some((k, b)) = self.blocks.get_key_value(&key) {
                    held.push((k, b));
                }
            });
        } else {
            held.extend(self.blocks.iter());
        }
        for (key, block) in held {
            let (blo, bhi) = self.block_box(key);
            let from: Vec<usize> = blo.iter().zip(lo).map(|(a, b)| *a.max(b)).collect();
            let to: Vec<usize> = bhi.iter().zip(hi).map(|(a, b)| *a.min(b)).collect();
            if from.iter().zip(&to).any(|(f, t)| f >= t) {
                continue;
            }
            let bdims: Vec<usize> = blo.iter().zip(&bhi).map(|(l, h)| h - l).collect();
            let inter: Vec<usize> = from.iter().zip(&to).map(|(f, t)| t - f).collect();
            // Row by row along the last axis (0-d: the one sample).
            let Some(last) = inter.len().checked_sub(1) else {
                out[0] = block[0].clone();
                continue;
            };
            let row = inter[last];
            super::gather::for_each_index(&inter[..last], |_, idx| {
                let (mut o, mut b) = (0, 0);
                for a in 0..last {
                    let g = from[a] + idx[a];
                    o = o * dims[a] + (g - lo[a]);
                    b = b * bdims[a] + (g - blo[a]);
                }
                o = o * dims[last] + (from[last] - lo[last]);
                b = b * bdims[last] + (from[last] - blo[last]);
                out[o..o + row].clone_from_slice(&block[b..b + row]);
            });
        }
    }

    /// Every changed block: its first index and its samples (for pickling).
    pub(crate) fn blocks(&self) -> Vec<(Vec<usize>, Vec<T>)> {
        self.blocks
            .iter()
            .map(|(k, b)| (self.block_box(k).0, b.clone()))
            .collect()
    }

    /// Restores a block saved by [`Self::blocks`].
    pub(crate) fn restore(&mut self, first: &[usize], data: Vec<T>) -> Result<(), NdimageError> {
        let key: Vec<usize> = first.iter().zip(&self.edge).map(|(i, e)| i / e).collect();
        let (lo, hi) = self.block_box(&key);
        let size: usize = lo.iter().zip(&hi).map(|(l, h)| h - l).product();
        if first != lo.as_slice() || data.len() != size {
            return Err(NdimageError::BufferLength {
                expected: size,
                got: data.len(),
            });
        }
        self.blocks.insert(key, data);
        Ok(())
    }
}

/// What one [`Overlay::set_all`] changed: the blocks it added, and per
/// change its block, position and old value.
pub(crate) struct Undo<T> {
    added: Vec<Vec<usize>>,
    old: Vec<(Vec<usize>, usize, T)>,
}

/// A source read through an [`Overlay`] of changed samples.
pub(crate) struct Overlaid<'a, T, S: ?Sized> {
    pub(crate) base: &'a S,
    pub(crate) overlay: &'a Overlay<T>,
}

impl<T: Real + Sync, S: SampleSource<T> + ?Sized> SampleSource<T> for Overlaid<'_, T, S> {
    fn shape(&self) -> &[usize] {
        self.base.shape()
    }

    fn read_box(&self, lo: &[usize], hi: &[usize], out: &mut [T]) -> Result<(), NdimageError> {
        self.base.read_box(lo, hi, out)?;
        self.overlay.patch(lo, hi, out);
        Ok(())
    }
}
