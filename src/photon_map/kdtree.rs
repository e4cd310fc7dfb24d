//! A kd-tree over points stored as f32.

/// A point the kd-tree can hold.
pub trait KdPoint: Copy + Send + Sync {
    fn position(&self) -> [f32; 3];
}

/// Result buffer of a k-nearest query: (index, squared distance) pairs.
#[derive(Clone, Debug, Default)]
pub struct Neighbours {
    pub items: Vec<(u32, f32)>,
}

impl Neighbours {
    pub fn len(&self) -> usize {
        self.items.len()
    }
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
    /// Largest squared distance among the items (0 if empty).
    pub fn max_dist2(&self) -> f32 {
        todo!()
    }
}

#[derive(Clone, Debug)]
pub struct KdTree<T> {
    items: Vec<T>,
}

impl<T: KdPoint> KdTree<T> {
    pub fn build(items: Vec<T>) -> KdTree<T> {
        todo!("{}", items.len())
    }
    pub fn len(&self) -> usize {
        self.items.len()
    }
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
    pub fn items(&self) -> &[T] {
        &self.items
    }
    /// The up-to-`k` items nearest to `q` with squared distance ≤ `max_dist2`.
    pub fn knn(&self, q: [f32; 3], k: usize, max_dist2: f32, out: &mut Neighbours) {
        todo!("{q:?}{k}{max_dist2}{}", out.len())
    }
}
