//! The tiles of coefficients a [`LocalInterpolant`](super::LocalInterpolant)
//! keeps between calls, within a byte budget: the least recently used tile
//! goes first when a new one does not fit.

use super::coef_box::CoefBox;
use std::collections::{BTreeMap, HashMap};
use std::sync::{Arc, Mutex};

/// A tile: its coefficients and when it was last used.
struct Entry<T> {
    tile: Arc<CoefBox<T>>,
    used: u64,
}

/// The cache proper, behind the lock.
struct Tiles<T> {
    map: HashMap<Vec<i64>, Entry<T>>,
    /// Last use → key, oldest first.
    order: BTreeMap<u64, Vec<i64>>,
    clock: u64,
    bytes: usize,
}

/// Tiles within a byte budget, least recently used evicted first.
pub(crate) struct TileCache<T> {
    inner: Mutex<Tiles<T>>,
    budget: usize,
}

impl<T> TileCache<T> {
    /// An empty cache of `budget` bytes.
    pub(crate) fn new(budget: usize) -> Self {
        TileCache {
            inner: Mutex::new(Tiles {
                map: HashMap::new(),
                order: BTreeMap::new(),
                clock: 0,
                bytes: 0,
            }),
            budget,
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Tiles<T>> {
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The budget in bytes.
    pub(crate) fn budget(&self) -> usize {
        self.budget
    }

    /// Bytes held now.
    pub(crate) fn bytes(&self) -> usize {
        self.lock().bytes
    }

    /// Tiles held now.
    pub(crate) fn len(&self) -> usize {
        self.lock().map.len()
    }

    /// The tile at `key`, marked used.
    pub(crate) fn get(&self, key: &[i64]) -> Option<Arc<CoefBox<T>>> {
        let mut t = self.lock();
        t.clock += 1;
        let now = t.clock;
        let e = t.map.get_mut(key)?;
        let old = std::mem::replace(&mut e.used, now);
        let tile = e.tile.clone();
        t.order.remove(&old);
        t.order.insert(now, key.to_vec());
        Some(tile)
    }

    /// Keeps `tile` at `key`, evicting the oldest tiles until it fits.
    pub(crate) fn put(&self, key: Vec<i64>, tile: Arc<CoefBox<T>>) {
        let size = tile.data.len() * std::mem::size_of::<T>();
        if size > self.budget {
            return;
        }
        let mut t = self.lock();
        if let Some(old) = t.map.remove(&key) {
            t.order.remove(&old.used);
            t.bytes -= old.tile.data.len() * std::mem::size_of::<T>();
        }
        while t.bytes + size > self.budget {
            let Some((_, oldest)) = t.order.pop_first() else {
                break;
            };
            if let Some(e) = t.map.remove(&oldest) {
                t.bytes -= e.tile.data.len() * std::mem::size_of::<T>();
            }
        }
        t.clock += 1;
        let used = t.clock;
        t.order.insert(used, key.clone());
        t.bytes += size;
        t.map.insert(key, Entry { tile, used });
    }

    /// The keys and tiles held now for which `pick` says `Some`, with
    /// what it says (an update's tiles within reach: only those are
    /// copied out of the lock, not every key).
    pub(crate) fn select<X>(
        &self,
        mut pick: impl FnMut(&CoefBox<T>) -> Option<X>,
    ) -> Vec<(Vec<i64>, Arc<CoefBox<T>>, X)> {
        self.lock()
            .map
            .iter()
            .filter_map(|(k, e)| pick(&e.tile).map(|x| (k.clone(), e.tile.clone(), x)))
            .collect()
    }

    /// Replaces the tile at `key` if it is still held (its size unchanged).
    pub(crate) fn replace(&self, key: &[i64], tile: Arc<CoefBox<T>>) {
        if let Some(e) = self.lock().map.get_mut(key) {
            e.tile = tile;
        }
    }

    /// Drops the tile at `key`, if held.
    pub(crate) fn remove(&self, key: &[i64]) {
        let mut t = self.lock();
        if let Some(e) = t.map.remove(key) {
            t.order.remove(&e.used);
            t.bytes -= e.tile.data.len() * std::mem::size_of::<T>();
        }
    }

    /// Drops every tile.
    pub(crate) fn clear(&self) {
        let mut t = self.lock();
        t.map.clear();
        t.order.clear();
        t.bytes = 0;
    }
}
