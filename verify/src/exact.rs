//! Exact rational linear algebra: the ground truth for systems whose entries
//! are rationals (f64 inputs, exact node values).

use rug::Rational;

/// Solves `A x = b` exactly by Gaussian elimination over the rationals
/// (first non-zero pivot). `None` when `A` is singular or not square with
/// `b` of matching length. Cost `O(n³)` rational operations, whose sizes
/// grow: keep `n` to a few dozen.
pub fn solve_rational(mut a: Vec<Vec<Rational>>, b: &[Rational]) -> Option<Vec<Rational>> {
    let n = b.len();
    if a.len() != n || a.iter().any(|row| row.len() != n) {
        return None;
    }
    for (row, bj) in a.iter_mut().zip(b) {
        row.push(bj.clone());
    }
    for k in 0..n {
        let p = (k..n).find(|&r| a[r][k] != 0)?;
        a.swap(k, p);
        for r in k + 1..n {
            if a[r][k] == 0 {
                continue;
            }
            let f = a[r][k].clone() / a[k][k].clone();
            let (top, bottom) = a.split_at_mut(r);
            for (x, y) in bottom[0].iter_mut().zip(&top[k]).skip(k) {
                *x -= f.clone() * y;
            }
        }
    }
    let mut x = vec![Rational::new(); n];
    for k in (0..n).rev() {
        let mut s = a[k][n].clone();
        for j in k + 1..n {
            s -= a[k][j].clone() * x[j].clone();
        }
        x[k] = s / a[k][k].clone();
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_small_system_and_refuses_a_singular_one() {
        let q = |n: i32, d: i32| Rational::from((n, d));
        // [[2, 1], [1, 3]] x = [1, 2] has x = (1/5, 3/5).
        let a = vec![vec![q(2, 1), q(1, 1)], vec![q(1, 1), q(3, 1)]];
        let x = solve_rational(a, &[q(1, 1), q(2, 1)]).unwrap();
        assert_eq!(x, vec![q(1, 5), q(3, 5)]);
        let s = vec![vec![q(1, 1), q(2, 1)], vec![q(2, 1), q(4, 1)]];
        assert!(solve_rational(s, &[q(1, 1), q(1, 1)]).is_none());
    }
}
