// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Umbrella header of the clustering-quality metrics (namespace
/// streamclust::eval): adjusted Rand index, TRAVEL's OSE / USE, panoptic
/// matching at IoU > 0.5, coverage, object outcome rates, and evaluate()
/// bundling them into a QualityReport, QualityAverage over frames and
/// recovery_after for a metric's time series, evaluate_on_labelled for
/// scores on the points a reference method labelled; object_metrics for a
/// pipeline that removes ground, walls and ceiling (strict object rates,
/// object-point coverage, ground / wall / ceiling precision and recall),
/// ObjectMetricsAverage, and RangeCoverage (object-point coverage per range
/// band).
/// Definitions: docs/evaluation-metrics.md.
///
/// Inputs: per-point ground-truth instance ids (0 = structure, > 0 = object,
/// < 0 = ignored) and predicted cluster ids (< 0 = unlabelled), same length.
/// Every function is pure (thread-safe) and O(n log n) at most.

#include <streamclust/eval/average.hpp>
#include <streamclust/eval/contingency.hpp>
#include <streamclust/eval/coverage.hpp>
#include <streamclust/eval/labelled_subset.hpp>
#include <streamclust/eval/object_average.hpp>
#include <streamclust/eval/object_metrics.hpp>
#include <streamclust/eval/object_rates.hpp>
#include <streamclust/eval/options.hpp>
#include <streamclust/eval/panoptic.hpp>
#include <streamclust/eval/range_coverage.hpp>
#include <streamclust/eval/rand_index.hpp>
#include <streamclust/eval/recovery.hpp>
#include <streamclust/eval/report.hpp>
#include <streamclust/eval/segmentation_entropy.hpp>
#include <streamclust/eval/strict_object_rates.hpp>
#include <streamclust/eval/surface_scores.hpp>
