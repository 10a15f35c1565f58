//! The three directions a face is asked about in an epoch — towards the observer, the Sun
//! and the Earth ([`Toward`]) — and a value for each ([`PerDirection`]): what both
//! visibility engines (`visibility`, `silhouettes`) hold and decide per direction.

use std::ops::{Index, IndexMut};

/// One of the directions a face is asked about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Toward {
    /// Towards the observer: a face is seen where no sheet lies above it this way.
    View,
    /// Towards the Sun: sunlit where none does.
    Sun,
    /// Towards the Earth (earthshine's shadows).
    Earth,
}

impl Toward {
    /// Every direction, in the order [`PerDirection`] holds and visits them.
    pub const ALL: [Toward; 3] = [Toward::View, Toward::Sun, Toward::Earth];

    /// This direction's bit in a set of directions held as bits (view 1, Sun 2, Earth 4).
    #[inline]
    pub const fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// A value per direction. Iteration and [`PerDirection::map`] visit view, Sun, Earth in
/// that order (the order the steps were written for: the view first, since a face
/// unseen needs nothing else).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PerDirection<T> {
    pub view: T,
    pub sun: T,
    pub earth: T,
}

impl<T> PerDirection<T> {
    /// The same value along every direction.
    pub fn splat(value: T) -> Self
    where
        T: Clone,
    {
        PerDirection {
            view: value.clone(),
            sun: value.clone(),
            earth: value,
        }
    }

    /// A value per direction from `f`, called for view, Sun, Earth in that order.
    pub fn from_fn(mut f: impl FnMut(Toward) -> T) -> Self {
        let view = f(Toward::View);
        let sun = f(Toward::Sun);
        let earth = f(Toward::Earth);
        PerDirection { view, sun, earth }
    }

    /// `f` of each value, called for view, Sun, Earth in that order.
    pub fn map<U>(self, mut f: impl FnMut(T) -> U) -> PerDirection<U> {
        let view = f(self.view);
        let sun = f(self.sun);
        let earth = f(self.earth);
        PerDirection { view, sun, earth }
    }

    /// A reference to each value.
    pub fn each_ref(&self) -> PerDirection<&T> {
        PerDirection {
            view: &self.view,
            sun: &self.sun,
            earth: &self.earth,
        }
    }

    /// A mutable reference to each value.
    pub fn each_mut(&mut self) -> PerDirection<&mut T> {
        PerDirection {
            view: &mut self.view,
            sun: &mut self.sun,
            earth: &mut self.earth,
        }
    }

    /// The values paired with `other`'s, direction by direction.
    pub fn zip<U>(self, other: PerDirection<U>) -> PerDirection<(T, U)> {
        PerDirection {
            view: (self.view, other.view),
            sun: (self.sun, other.sun),
            earth: (self.earth, other.earth),
        }
    }

    /// The values, view first.
    pub fn iter(&self) -> std::array::IntoIter<&T, 3> {
        [&self.view, &self.sun, &self.earth].into_iter()
    }

    /// The values, view first.
    pub fn iter_mut(&mut self) -> std::array::IntoIter<&mut T, 3> {
        [&mut self.view, &mut self.sun, &mut self.earth].into_iter()
    }

    /// Each direction with its value, view first.
    pub fn pairs(&self) -> impl Iterator<Item = (Toward, &T)> {
        Toward::ALL.into_iter().zip(self.iter())
    }
}

impl<T> Index<Toward> for PerDirection<T> {
    type Output = T;

    #[inline]
    fn index(&self, k: Toward) -> &T {
        match k {
            Toward::View => &self.view,
            Toward::Sun => &self.sun,
            Toward::Earth => &self.earth,
        }
    }
}

impl<T> IndexMut<Toward> for PerDirection<T> {
    #[inline]
    fn index_mut(&mut self, k: Toward) -> &mut T {
        match k {
            Toward::View => &mut self.view,
            Toward::Sun => &mut self.sun,
            Toward::Earth => &mut self.earth,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_direction_has_its_own_field_and_bit_visited_view_first() {
        let mut seen = Vec::new();
        let mut values = PerDirection::from_fn(|k| {
            seen.push(k);
            k.bit()
        });
        // from_fn visits view, Sun, Earth in that order, as ALL lists them
        assert_eq!(seen, Toward::ALL);
        assert_eq!((values.view, values.sun, values.earth), (1, 2, 4));
        // indexing by direction reads and writes that direction's field alone
        values[Toward::Earth] = 9;
        assert_eq!(
            values,
            PerDirection {
                view: 1,
                sun: 2,
                earth: 9
            }
        );
        let pairs: Vec<(Toward, u8)> = values.pairs().map(|(k, &v)| (k, v)).collect();
        assert_eq!(
            pairs,
            [(Toward::View, 1), (Toward::Sun, 2), (Toward::Earth, 9)]
        );
        // the bits are a set: each direction's is distinct from the others' union
        for k in Toward::ALL {
            let others = Toward::ALL
                .iter()
                .filter(|&&o| o != k)
                .fold(0, |m, o| m | o.bit());
            assert_eq!(k.bit() & others, 0, "{k:?}");
        }
    }
}
