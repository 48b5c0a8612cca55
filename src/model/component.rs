//! [`PerComponent`]: one value per launch component, indexed by [`LaunchComponent`] rather
//! than by position.

use std::ops::{Deref, DerefMut, Index, IndexMut};

use crate::physics::LaunchComponent;

/// One value per [`LaunchComponent`], in [`LaunchComponent::ALL`] (file) order. Index it with a
/// component (`errors[LaunchComponent::Backspin]`); it dereferences to the array for slice
/// operations.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PerComponent<T>(pub [T; 5]);

impl<T> PerComponent<T> {
    /// The value of each component from `f`.
    pub fn from_fn(mut f: impl FnMut(LaunchComponent) -> T) -> Self {
        Self(LaunchComponent::ALL.map(&mut f))
    }

    /// Each value mapped by `f`.
    pub fn map<U>(self, f: impl FnMut(T) -> U) -> PerComponent<U> {
        PerComponent(self.0.map(f))
    }

    /// `(component, value)` pairs in file order.
    pub fn pairs(&self) -> impl Iterator<Item = (LaunchComponent, &T)> {
        LaunchComponent::ALL.into_iter().zip(&self.0)
    }
}

impl<T> From<[T; 5]> for PerComponent<T> {
    fn from(a: [T; 5]) -> Self {
        Self(a)
    }
}

impl<T> Index<LaunchComponent> for PerComponent<T> {
    type Output = T;
    fn index(&self, c: LaunchComponent) -> &T {
        &self.0[c.index()]
    }
}

impl<T> IndexMut<LaunchComponent> for PerComponent<T> {
    fn index_mut(&mut self, c: LaunchComponent) -> &mut T {
        &mut self.0[c.index()]
    }
}

/// By position in [`LaunchComponent::ALL`], for code that walks the five in order.
impl<T> Index<usize> for PerComponent<T> {
    type Output = T;
    fn index(&self, i: usize) -> &T {
        &self.0[i]
    }
}

impl<T> Deref for PerComponent<T> {
    type Target = [T; 5];
    fn deref(&self) -> &[T; 5] {
        &self.0
    }
}

impl<T> DerefMut for PerComponent<T> {
    fn deref_mut(&mut self) -> &mut [T; 5] {
        &mut self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn components_index_their_own_slot() {
        let p = PerComponent::from_fn(|c| c.column());
        for c in LaunchComponent::ALL {
            assert_eq!(p[c], c.column());
        }
        let mut q = p.map(str::len);
        q[LaunchComponent::Sidespin] = 0;
        assert_eq!(q[4], 0);
        assert_eq!(q.pairs().count(), 5);
    }
}
