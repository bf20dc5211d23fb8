!> Replicated contact on several ranks: the surface positions gathered from
!> their owners are bitwise those of the global mesh, so every rank's search
!> finds exactly the pairs of a serial search on the global positions.
program test_contact_parallel
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use mesh_global, only: global_mesh_t, box_spec_t, mesh_make_box
  use mesh_local, only: mesh_t, mesh_build_local
  use parallel_env, only: par_init, par_finalize, par_size, par_min
  use parallel_partition, only: partition_zones
  use parallel_gather, only: gather_by_id
  use contact_surface, only: contact_surface_t, surface_build
  use contact_search, only: bucket_search
  use check, only: check_true, check_summary
  implicit none
  type(box_spec_t) :: spec
  type(global_mesh_t) :: global
  type(mesh_t) :: mesh
  type(status_t) :: status
  type(contact_surface_t) :: bottom, top
  integer(ik), allocatable :: part(:)
  integer(i8), allocatable :: ids(:), owned(:)
  real(rk), allocatable :: xglobal(:, :), xowned(:, :), gathered(:, :), xsearch(:, :)
  integer, allocatable :: pairs_ref(:, :), pairs(:, :)
  integer :: n, i, same

  call par_init()
  ! A thin box whose bottom nodes search its top segments, every node moved
  ! by a smooth deterministic field so the pairs are not trivial.
  spec%nint = 1
  spec%breaks(0:1, 1) = [0.0_rk, 1.0_rk]
  spec%breaks(0:1, 2) = [0.0_rk, 1.0_rk]
  spec%breaks(0:1, 3) = [0.0_rk, 0.02_rk]
  spec%zones(1, :) = [20, 16, 1]
  call mesh_make_box(spec, global, status)
  do n = 1, global%nnode
    global%coordinates(:, n) = global%coordinates(:, n) + 0.004_rk * &
        [sin(7.0_rk * n), cos(5.0_rk * n), sin(3.0_rk * n)]
  end do
  allocate(part(global%nzone))
  call partition_zones(global%nnode, global%connectivity, par_size(), part)
  call mesh_build_local(global, part, mesh)
  call surface_build(global, ['zmin'], bottom, status)
  call surface_build(global, ['zmax'], top, status)
  call check_true('surfaces built', status%ok())

  ! Serial reference on the global positions.
  call bucket_search(global%coordinates, bottom, top, .false., 0.05_rk, pairs_ref)

  ! Replicated: positions of the surface nodes from their owners only.
  ids = [int(bottom%nodes, i8), int(top%nodes, i8)]
  call sort_unique(ids)
  owned = mesh%node_gid(1:mesh%nnode_owned)
  allocate(xowned(3, mesh%nnode_owned), gathered(3, size(ids)))
  xowned = global%coordinates(:, owned)
  call gather_by_id(ids, owned, xowned, gathered)
  xglobal = global%coordinates
  same = 1
  do i = 1, size(ids)
    if (any(gathered(:, i) /= xglobal(:, ids(i)))) same = 0
  end do
  call check_true('gathered positions bitwise equal to the global ones', &
      par_min(same) == 1)
  allocate(xsearch(3, global%nnode))
  xsearch = huge(1.0_rk)
  xsearch(:, ids) = gathered
  call bucket_search(xsearch, bottom, top, .false., 0.05_rk, pairs)
  same = 0
  if (size(pairs, 2) == size(pairs_ref, 2)) then
    if (all(pairs == pairs_ref)) same = 1
  end if
  call check_true('every rank finds exactly the serial pairs', par_min(same) == 1)
  call check_true('pairs found', size(pairs, 2) > 0)
  call par_finalize()
  call check_summary()

contains

  subroutine sort_unique(a)
    integer(i8), allocatable, intent(inout) :: a(:)
    integer(i8), allocatable :: b(:)
    integer :: p, q, k
    integer(i8) :: t
    ! insertion sort is enough for a few hundred ids
    do p = 2, size(a)
      t = a(p)
      q = p - 1
      do while (q >= 1)
        if (a(q) <= t) exit
        a(q + 1) = a(q)
        q = q - 1
      end do
      a(q + 1) = t
    end do
    allocate(b(size(a)))
    k = 0
    do p = 1, size(a)
      if (k > 0) then
        if (b(k) == a(p)) cycle
      end if
      k = k + 1
      b(k) = a(p)
    end do
    a = b(1:k)
  end subroutine sort_unique

end program test_contact_parallel
