//! Regression, ANOVA and hypothesis tests with Design-Expert conventions (issue 3).
