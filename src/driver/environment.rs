//! The environment's turn in a derivation (an open L-system): the `?E`
//! modules met while the word is interpreted become queries as cpfg sends
//! them (their parameters printed `%g`, the turtle's position with the
//! `.e` file's format, each read back as the program reads it), the
//! program ([`crate::enviro`]) answers the step's queries, and each answer
//! is written into its module's parameters as cpfg writes it.

use crate::enviro::{Answer, Pass, Query};
use crate::ir::environment::Environment;
use crate::ir::Word;
use crate::turtle::{printf, Vec3};

/// The `?E` modules of one interpretation of the word, in its order.
#[derive(Default)]
pub(super) struct Asked {
    queries: Vec<Query>,
    /// Per query, the module of the word its answer goes to; `None` for a
    /// `?E` the homomorphism made (sent, its answer dropped, as in cpfg).
    targets: Vec<Option<usize>>,
}

impl Asked {
    /// A `?E` with parameters `params` met at `position`; `target`: the
    /// module of the word it is.
    pub(super) fn push(
        &mut self,
        env: &Environment,
        target: Option<usize>,
        params: &[f64],
        position: Vec3,
    ) {
        self.queries.push(Query {
            params: params.iter().map(|&p| through_g(p)).collect(),
            position: env
                .position
                .as_deref()
                .map_or_else(Vec::new, |f| sent_position(f, position)),
        });
        self.targets.push(target);
    }

    /// The program's answers to the queries, written into `word`.
    pub(super) fn answer(self, program: &mut dyn Pass, word: &mut Word) {
        if self.queries.is_empty() {
            // cpfg tells the program nothing of a step without queries.
            return;
        }
        let answers = program.answer(&self.queries);
        for (target, answer) in self.targets.into_iter().zip(answers) {
            if let Some(o) = target.filter(|&o| o < word.len()) {
                write(word, o, &answer);
            }
        }
    }
}

/// Writes `answer` into the parameters of module `o`: value k over
/// parameter k, through `%g` as cpfg reads it; a value left unset, or past
/// the module's parameters, changes nothing.
fn write(word: &mut Word, o: usize, answer: &Answer) {
    let mut args = word.args(o).to_vec();
    let mut changed = false;
    for (slot, value) in args.iter_mut().zip(answer) {
        if let Some(v) = value {
            *slot = f64::from(through_g(f64::from(*v)));
            changed = true;
        }
    }
    if changed {
        word.set_args(o, &args);
    }
}

/// A number as it arrives through cpfg's text: printed `%g` (six
/// significant digits), read back as a C `float`.
fn through_g(x: f64) -> f32 {
    crate::number::leading(&printf("%g", &[x])).unwrap_or(0.0) as f32
}

/// The position as the program reads it: `format` prints the turtle's
/// `float` coordinates; the program skips the text before the format's
/// first `%` and reads as many numbers as the format has conversions (at
/// most three), each up to the first that fails.
fn sent_position(format: &str, p: Vec3) -> Vec<f32> {
    let values = p.map(|c| f64::from(c as f32));
    let printed = printf(format, &values);
    let skip = format.find('%').unwrap_or(format.len());
    let conversions = format.matches('%').count() - 2 * format.matches("%%").count();
    let mut out = Vec::new();
    for token in printed.get(skip..).unwrap_or("").split_whitespace() {
        if out.len() >= conversions.min(3) {
            break;
        }
        match crate::number::leading(token) {
            Some(x) => out.push(x as f32),
            None => break,
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_position_arrives_as_the_format_prints_it() {
        assert_eq!(
            sent_position("P:%.4f %.4f %.0f", [0.123456, -2.5, 3.7]),
            vec![0.1235, -2.5, 4.0]
        );
        assert_eq!(
            sent_position("P:%.4g %.4g %.4g", [12.34567, 0.0, 1.0]),
            vec![12.35, 0.0, 1.0]
        );
        // Two conversions: the third value is never read.
        assert_eq!(
            sent_position("P:%.4f %.4f", [1.0, 2.0, 3.0]),
            vec![1.0, 2.0]
        );
        assert_eq!(
            sent_position(" %.4f %.4f %.4f", [1.0, 2.0, 3.0]),
            vec![1.0, 2.0, 3.0]
        );
    }

    #[test]
    fn parameters_travel_with_six_digits() {
        assert_eq!(through_g(0.123456789), 0.123457);
        assert_eq!(through_g(1234567.0), 1234570.0);
    }

    #[test]
    fn an_answer_sets_what_it_sets_and_keeps_the_rest() {
        let mut sys = crate::ir::System::new();
        let e = sys.symbols.intern("?E");
        let mut word = Word::default();
        word.push(e, &[5.0, 6.0]);
        write(&mut word, 0, &vec![None, Some(0.25), Some(9.0)]);
        assert_eq!(word.args(0), &[5.0, 0.25]);
    }
}
