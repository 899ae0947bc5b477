//! A guard file's node tables run by the executor's evaluator
//! (`executor::guards`) give what the BDDs give, on every state tuple of
//! small family instances.

use des_symbolic::guard_file::GuardFile;
use des_symbolic::{families, synthesize};
use executor::guards::{GuardNode, GuardTable, StateBit};

/// The executor's bit sources of `file`: bit `b` of the state code is bit
/// `bits − 1 − k` of the component whose `k`-th bit it is.
fn state_bits(file: &GuardFile) -> Vec<StateBit> {
    let total: u32 = file.components.iter().map(|c| c.bits).sum();
    let mut bits = vec![
        StateBit {
            component: 0,
            shift: 0
        };
        total as usize
    ];
    for (c, comp) in file.components.iter().enumerate() {
        for k in 0..comp.bits {
            bits[(comp.first_bit + k) as usize] = StateBit {
                component: c as u16,
                shift: (comp.bits - 1 - k) as u8,
            };
        }
    }
    bits
}

#[test]
fn the_executor_evaluates_guard_tables_as_the_bdds_do() {
    let instances = [
        families::ring(3).unwrap(),
        families::ring_breakdowns(3).unwrap(),
        families::tline(3).unwrap(),
        families::module(2).unwrap(),
    ];
    let mut compared = 0;
    for f in instances {
        let s = synthesize(&f.plants, &f.specs).unwrap();
        let file = GuardFile::new(&f.name, &s, &f.plants, &f.specs);
        let bits: Vec<[u32; 1]> = state_bits(&file).iter().map(StateBit::to_words).collect();
        let tables: Vec<(String, u16, Vec<[u32; 2]>)> = file
            .guards
            .iter()
            .map(|g| {
                let nodes = g
                    .nodes
                    .iter()
                    .map(|&[bit, low, high]| {
                        GuardNode {
                            bit: bit as u16,
                            low: low as u16,
                            high: high as u16,
                        }
                        .to_words()
                    })
                    .collect();
                (g.event.clone(), g.root as u16, nodes)
            })
            .collect();
        let sizes: Vec<u32> = file
            .components
            .iter()
            .map(|c| c.states.len() as u32)
            .collect();
        let mut tuple = vec![0u32; sizes.len()];
        'tuples: loop {
            for (event, root, nodes) in &tables {
                let table = GuardTable { root: *root, nodes };
                assert_eq!(
                    table.eval(&bits, &tuple),
                    file.allows(event, &tuple),
                    "{}: {event} at {tuple:?}",
                    f.name
                );
                compared += 1;
            }
            for (x, &size) in tuple.iter_mut().zip(&sizes) {
                *x += 1;
                if *x < size {
                    continue 'tuples;
                }
                *x = 0;
            }
            break;
        }
    }
    assert!(compared > 10_000, "{compared}");
}
