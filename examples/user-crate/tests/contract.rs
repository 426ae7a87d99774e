/// The framework's contract test, run on this crate's own method.
#[test]
fn laplacian_keeps_the_contract() {
    fairing::catalog::contract::assert_curve_method(&laplacian_fair::catalog(), "laplacian");
}
