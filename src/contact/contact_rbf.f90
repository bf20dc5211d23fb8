!> Radial basis function weights for the "put-back-on" step of the DAM contact method: a
!> scalar field known at k master nodes (normal acceleration, normal velocity, ...) is
!> interpolated to a slave point. rbf_weights returns weights w(1:k) such that the
!> interpolated value is sum_j w(j) f(j) for any nodal field f, so one linear solve
!> serves every field the caller interpolates.
!>
!> Coordinates. Everything is done in 2D coordinates of the tangent plane with the given
!> unit normal n. A linear term in 3D coordinates would make the system singular whenever
!> the master nodes are coplanar (the usual case), so the nodes are projected: with
!> tangents t1, t2, node j gets q(j) = (t1 . (x(j) - p), t2 . (x(j) - p)), p the slave
!> point; the component along n is dropped. The tangents are a deterministic function of
!> n alone: a is the coordinate axis along which |n| has its smallest component (first
!> such axis on ties), t1 = n x e_a / |n x e_a| (|n x e_a| >= sqrt(2/3), so no
!> cancellation), t2 = n x t1. The coordinates are then divided by the largest node
!> distance from p, so all of them lie in the unit disc, the matrix entries are O(1) and
!> the conditioning does not depend on the length unit. Centring at p makes the
!> polynomial part of the right-hand side (1, 0, 0).
!>
!> Basis. The radial function is the thin plate spline phi(r) = r^2 log r (phi(0) = 0),
!> the polyharmonic spline that minimises the bending energy in 2D. It has no shape
!> parameter to tune (unlike multiquadrics or Gaussians, whose accuracy and conditioning
!> hinge on one), and it is conditionally positive definite of order 2: the quadratic form
!> of its matrix is positive on coefficient vectors orthogonal to the linear polynomials
!> (1, u, v). Augmenting with exactly that polynomial space therefore makes the saddle-point
!> system below nonsingular for any set of distinct nodes not all on one line, and its
!> constraint rows reproduce constant and linear fields exactly. The interpolant does not
!> depend on the scaling of the coordinates: phi(s r) = s^2 phi(r) + s^2 log(s) r^2, and
!> sum_j c(j) |q - q(j)|^2 is a constant (absorbed by the polynomial) because the
!> coefficients satisfy sum c = 0 and sum c q = 0. Scaling only improves the conditioning.
!>
!> System. With Phi(i, j) = phi(|q(i) - q(j)|) and P(j, :) = (1, u(j), v(j)), the
!> interpolant of f is s(q) = sum_j c(j) phi(|q - q(j)|) + d . (1, u, v), where
!> [Phi P; P^T 0] [c; d] = [f; 0]. The matrix M is symmetric, so the value at the point,
!> [phi0; p0]^T M^-1 [f; 0], equals w . f with [w; mu] = M^-1 [phi0; p0],
!> phi0(j) = phi(|q(j)|) and p0 = (1, 0, 0): one solve with one right-hand side. Its last
!> three rows read sum w = 1, sum w u = 0, sum w v = 0, which is constant and linear
!> reproduction in the plane (to round-off). M is indefinite (zero polynomial block); for
!> the small k of a contact patch (up to about 16, n = k + 3) the LU factorisation with
!> partial pivoting of LAPACK dgesv is robust and its cost is negligible, so the symmetric
!> indefinite solver dsysv (and its workspace query) buys nothing. At a node the
!> right-hand side is a column of M and w is the unit vector to round-off.
!>
!> Degenerate input, ok = .false. The system is singular when two nodes project onto the
!> same point of the plane (two equal rows) or when all nodes lie on one line in the plane
!> (the polynomial block P has rank < 3), which includes k < 3. Both are tested before the
!> solve on the projected coordinates, relative to the node cloud (so independent of the
!> point and of units): coincident if two nodes are closer than COINCIDENT_TOL times the
!> largest node separation; collinear if the smaller principal second moment of the nodes
!> is below COLLINEAR_TOL^2 times the larger one (width below COLLINEAR_TOL times length).
!> A failed solve (info /= 0, non-finite weights, constraint residual above
!> RESIDUAL_TOL sum |w|) is treated alike, and so is a zero normal. Then w holds
!> inverse-distance-squared (Shepard) weights on the in-plane distances (3D distances for a
!> zero normal): nonnegative, summing to 1, the whole weight shared by the nodes at the
!> point if there are any, and 1/k each if every node projects onto the point. These
!> reproduce constants only.
!>
!> Determinism. The weights are a function of the nodes, the point and the normal;
!> permuting the nodes permutes the weights up to round-off (pivot order and summation
!> order follow the node order). The caller orders the nodes by global id, so for a given
!> mesh and build the results do not depend on the partitioning.
!>
!> LAPACK is declared below with an explicit interface (the code is compiled with
!> -Wimplicit-interface). The interface is marked pure so that rbf_weights can be pure:
!> dgesv only writes its arguments; its error handler is reached only for invalid
!> arguments, which this module never passes. The real kind rk must be double precision.
!> Finite input is assumed.
module contact_rbf
  use core_kinds, only: rk
  implicit none
  private
  public :: rbf_weights

  !> Two nodes closer in the plane than this fraction of the largest node separation
  !> are coincident.
  real(rk), parameter :: COINCIDENT_TOL = 1.0e-6_rk
  !> Nodes whose in-plane width (across their principal direction) is below this
  !> fraction of their length are collinear.
  real(rk), parameter :: COLLINEAR_TOL = 1.0e-6_rk
  !> Fallback: nodes within this fraction of the largest distance of the point take the
  !> whole weight (their inverse-square weight would exceed the others' by 1/epsilon).
  real(rk), parameter :: SNAP_TOL = 1.0e-8_rk
  !> Largest accepted residual of the constraint rows, relative to sum |w|.
  real(rk), parameter :: RESIDUAL_TOL = 1.0e-8_rk

  interface
    !> LAPACK: solve A X = B by LU factorisation with partial pivoting (double precision).
    pure subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: rk
      integer, intent(in) :: n, nrhs, lda, ldb
      real(rk), intent(inout) :: a(lda, *)
      integer, intent(out) :: ipiv(*)
      real(rk), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dgesv
  end interface

contains

  !> Weights w(k) so that the interpolant at point is sum_k w(k) f(k) for any nodal field
  !> f: thin plate spline plus linear polynomial in the tangent plane with unit normal
  !> `normal` (see the module header). nodes is (3, k) and w must have size k. ok is
  !> .false. for degenerate input (coincident or collinear nodes in the plane, k < 3, a
  !> zero normal); w then holds inverse-distance weights that still sum to 1.
  pure subroutine rbf_weights(nodes, point, normal, w, ok)
    real(rk), intent(in) :: nodes(:, :)   !< (3, k) master node positions, k >= 3
    real(rk), intent(in) :: point(3)      !< slave point
    real(rk), intent(in) :: normal(3)     !< unit normal of the tangent plane
    real(rk), intent(out) :: w(:)         !< (k) weights
    logical, intent(out) :: ok            !< .false. if degenerate (w = fallback weights)
    real(rk) :: q(2, size(nodes, 2)), dist(size(nodes, 2))
    real(rk) :: a(size(nodes, 2) + 3, size(nodes, 2) + 3), b(size(nodes, 2) + 3)
    integer :: ipiv(size(nodes, 2) + 3)
    real(rk) :: t1(3), t2(3), rel(3), scale, residual
    integer :: k, n, i, j, info
    logical :: basis_ok

    k = size(nodes, 2)
    ok = .false.
    if (k == 0) return
    call tangent_basis(normal, t1, t2, basis_ok)
    if (.not. basis_ok) then
      do j = 1, k
        dist(j) = norm2(nodes(:, j) - point)
      end do
      call fallback_weights(dist, w)
      return
    end if

    do j = 1, k
      rel = nodes(:, j) - point
      q(1, j) = dot_product(t1, rel)
      q(2, j) = dot_product(t2, rel)
      dist(j) = norm2(q(:, j))
    end do
    if (k < 3 .or. degenerate(q)) then
      call fallback_weights(dist, w)
      return
    end if

    ! Not degenerate, so the nodes are not all at the point: scale > 0.
    scale = maxval(dist)
    q = q / scale
    n = k + 3
    do j = 1, k
      do i = 1, k
        a(i, j) = tps(sum((q(:, i) - q(:, j))**2))
      end do
      a(j, k + 1) = 1.0_rk
      a(j, k + 2) = q(1, j)
      a(j, k + 3) = q(2, j)
      a(k + 1, j) = 1.0_rk
      a(k + 2, j) = q(1, j)
      a(k + 3, j) = q(2, j)
      b(j) = tps(sum(q(:, j)**2))
    end do
    a(k + 1:k + 3, k + 1:k + 3) = 0.0_rk
    b(k + 1:k + 3) = [1.0_rk, 0.0_rk, 0.0_rk]

    call dgesv(n, 1, a, n, ipiv, b, n, info)
    if (info /= 0) then
      call fallback_weights(dist, w)
      return
    end if
    if (.not. all(abs(b(1:k)) <= huge(1.0_rk))) then
      call fallback_weights(dist, w)
      return
    end if
    residual = abs(sum(b(1:k)) - 1.0_rk) + abs(sum(b(1:k) * q(1, :))) &
        + abs(sum(b(1:k) * q(2, :)))
    if (.not. residual <= RESIDUAL_TOL * sum(abs(b(1:k)))) then
      call fallback_weights(dist, w)
      return
    end if
    w = b(1:k)
    ok = .true.
  end subroutine rbf_weights

  !> Thin plate spline phi(r) = r^2 log r as a function of r2 = r^2; phi(0) = 0.
  elemental function tps(r2) result(phi)
    real(rk), intent(in) :: r2
    real(rk) :: phi
    if (r2 > 0.0_rk) then
      phi = 0.5_rk * r2 * log(r2)
    else
      phi = 0.0_rk
    end if
  end function tps

  pure function cross(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c(1) = a(2) * b(3) - a(3) * b(2)
    c(2) = a(3) * b(1) - a(1) * b(3)
    c(3) = a(1) * b(2) - a(2) * b(1)
  end function cross

  !> Orthonormal tangents t1, t2 of the plane with normal `normal` (normalised here):
  !> t1 = n x e_a / |n x e_a| with a the axis of the smallest |n(a)| (first on ties),
  !> t2 = n x t1. ok = .false. for a zero or non-finite normal.
  pure subroutine tangent_basis(normal, t1, t2, ok)
    real(rk), intent(in) :: normal(3)
    real(rk), intent(out) :: t1(3), t2(3)
    logical, intent(out) :: ok
    real(rk) :: length, unit(3), axis(3)
    integer :: ia

    t1 = 0.0_rk
    t2 = 0.0_rk
    length = norm2(normal)
    ok = length > 0.0_rk .and. length <= huge(1.0_rk)
    if (.not. ok) return
    unit = normal / length
    ia = 1
    if (abs(unit(2)) < abs(unit(ia))) ia = 2
    if (abs(unit(3)) < abs(unit(ia))) ia = 3
    axis = 0.0_rk
    axis(ia) = 1.0_rk
    t1 = cross(unit, axis)
    t1 = t1 / norm2(t1)
    t2 = cross(unit, t1)
  end subroutine tangent_basis

  !> True when the in-plane coordinates q(2, k) make the system singular: all nodes
  !> at one point, two nodes coincident, or all nodes on one line (see the module header).
  pure logical function degenerate(q)
    real(rk), intent(in) :: q(:, :)
    real(rk) :: r2, longest2, shortest2, centre(2), m11, m22, m12, largest, det
    integer :: k, i, j

    k = size(q, 2)
    longest2 = 0.0_rk
    shortest2 = huge(1.0_rk)
    do j = 2, k
      do i = 1, j - 1
        r2 = sum((q(:, i) - q(:, j))**2)
        longest2 = max(longest2, r2)
        shortest2 = min(shortest2, r2)
      end do
    end do
    degenerate = .true.
    if (.not. longest2 > 0.0_rk) return
    if (shortest2 <= COINCIDENT_TOL**2 * longest2) return
    ! Principal second moments about the centroid: largest and det = largest * smallest.
    centre = sum(q, dim=2) / k
    m11 = sum((q(1, :) - centre(1))**2)
    m22 = sum((q(2, :) - centre(2))**2)
    m12 = sum((q(1, :) - centre(1)) * (q(2, :) - centre(2)))
    largest = 0.5_rk * (m11 + m22) + sqrt(0.25_rk * (m11 - m22)**2 + m12**2)
    det = m11 * m22 - m12**2
    degenerate = det <= COLLINEAR_TOL**2 * largest**2
  end function degenerate

  !> Inverse-distance-squared weights from the distances dist(k) of the nodes to the
  !> point; they sum to 1. Nodes within SNAP_TOL of the largest distance share the whole
  !> weight; if every distance is zero each node gets 1/k.
  pure subroutine fallback_weights(dist, w)
    real(rk), intent(in) :: dist(:)
    real(rk), intent(out) :: w(:)
    real(rk) :: far
    logical :: near(size(dist))

    far = maxval(dist)
    if (.not. far > 0.0_rk) then
      w = 1.0_rk / size(dist)
      return
    end if
    near = dist <= SNAP_TOL * far
    if (any(near)) then
      w = merge(1.0_rk, 0.0_rk, near) / count(near)
    else
      w = (far / dist)**2
      w = w / sum(w)
    end if
  end subroutine fallback_weights

end module contact_rbf
